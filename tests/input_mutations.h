#pragma once
// Seeded edits of a valid input file, for the readers' robustness tests: a
// reader given any of them must either read it (and what it returns must
// hold the reader's own promises) or throw its typed error naming the file.
// Byte edits find what a damaged download does; token edits put the values a
// hand-edited or foreign file holds (nan, 1e309, counts beyond int, negative
// indices) where numbers stood, which random bytes almost never spell.
#include "mesh_ops/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <typeinfo>
#include <vector>

#include <sys/resource.h>

namespace mrcloth::test {

/// Caps this process's address space at 4 GiB, so that a reader reserving
/// memory without bound for a mutated count fails its test (std::bad_alloc
/// instead of InputError) instead of taking the machine's memory from the
/// tests beside it. Not under AddressSanitizer, which reserves terabytes
/// of shadow and reports such allocations itself.
inline void bound_memory() {
#if !defined(__SANITIZE_ADDRESS__)
  const rlimit limit{rlim_t{4} << 30, rlim_t{4} << 30};
  setrlimit(RLIMIT_AS, &limit);
#endif
}

/// Values that are numbers to a lenient reader and trouble to a strict one.
inline const std::vector<std::string>& hostile_numbers() {
  static const std::vector<std::string> tokens = {
      "nan",  "-nan", "NaN",        "inf",        "-inf",       "infinity",    "1e309",   "-1e309", "3.5e38",
      "1e38", "0",    "-0",         "-1",         "-2",         "2147483647",  "2147483648", "-2147483649",
      "4294967296", "99999999999999999999", "0x10", "1e-320", "1.5",      "+",           "-",       ".",
      "1e",   "e5",   "",           "00",         "1,5"};
  return tokens;
}

/// One to three edits of `text` drawn from `rng`: a byte replaced by one of
/// `alphabet`, a span erased, a line deleted, repeated or swapped with
/// another, a number replaced by or a hostile token inserted, or the text cut.
class TextMutator {
 public:
  TextMutator(std::uint32_t seed, std::string alphabet) : rng_(seed), alphabet_(std::move(alphabet)) {}

  std::string operator()(std::string text) {
    const int edits = 1 + static_cast<int>(rng_() % 3);
    for (int e = 0; e < edits && !text.empty(); ++e) edit(text);
    return text;
  }

 private:
  std::size_t below(std::size_t n) { return n == 0 ? 0 : rng_() % n; }

  /// [begin, end) of each line, newline excluded.
  static std::vector<std::pair<std::size_t, std::size_t>> lines(const std::string& text) {
    std::vector<std::pair<std::size_t, std::size_t>> spans;
    std::size_t begin = 0;
    while (begin < text.size()) {
      const std::size_t end = std::min(text.find('\n', begin), text.size());
      spans.emplace_back(begin, end);
      begin = end + 1;
    }
    return spans;
  }

  /// [begin, end) of each run of characters a number can be made of.
  static std::vector<std::pair<std::size_t, std::size_t>> numbers(const std::string& text) {
    std::vector<std::pair<std::size_t, std::size_t>> spans;
    const auto part = [](char c) { return (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '+' || c == 'e'; };
    for (std::size_t k = 0; k < text.size();) {
      if (text[k] >= '0' && text[k] <= '9') {
        std::size_t begin = k, end = k;
        while (begin > 0 && part(text[begin - 1]) && text[begin - 1] != 'e') --begin;
        while (end < text.size() && part(text[end])) ++end;
        spans.emplace_back(begin, end);
        k = end;
      } else {
        ++k;
      }
    }
    return spans;
  }

  void edit(std::string& text) {
    const auto& tokens = hostile_numbers();
    switch (rng_() % 8) {
      case 0:
        text[below(text.size())] = alphabet_[below(alphabet_.size())];
        break;
      case 1:
        text.erase(below(text.size()), 1 + below(8));
        break;
      case 2:
      case 3: {
        const auto spans = numbers(text);
        if (spans.empty()) break;
        const auto [begin, end] = spans[below(spans.size())];
        text.replace(begin, end - begin, tokens[below(tokens.size())]);
        break;
      }
      case 4:
        text.insert(below(text.size() + 1), " " + tokens[below(tokens.size())] + " ");
        break;
      case 5: {
        const auto spans = lines(text);
        if (spans.empty()) break;
        const auto [begin, end] = spans[below(spans.size())];
        if (rng_() % 2) text.erase(begin, std::min(end + 1, text.size()) - begin);
        else text.insert(begin, text.substr(begin, end - begin) + "\n");
        break;
      }
      case 6: {
        const auto spans = lines(text);
        if (spans.size() < 2) break;
        auto a = spans[below(spans.size())], b = spans[below(spans.size())];
        if (a.first > b.first) std::swap(a, b);
        if (a.first == b.first) break;
        const std::string first = text.substr(a.first, a.second - a.first);
        const std::string second = text.substr(b.first, b.second - b.first);
        text.replace(b.first, b.second - b.first, first);
        text.replace(a.first, a.second - a.first, second);
        break;
      }
      default:
        text.resize(below(text.size()));
        break;
    }
  }

  std::mt19937 rng_;
  std::string alphabet_;
};

/// One to three edits of binary `bytes` drawn from `rng`: a bit flipped, a
/// 32-bit word overwritten with a value readers trip on (0, -1, INT_MAX,
/// 2^31, NaN, inf, FLT_MAX as float), a span erased or repeated, or the
/// bytes cut. `protect` leading bytes (a header kept intact, when the body
/// is what is swept) are never edited.
class ByteMutator {
 public:
  ByteMutator(std::uint32_t seed, std::size_t protect = 0) : rng_(seed), protect_(protect) {}

  std::string operator()(std::string bytes) {
    const int edits = 1 + static_cast<int>(rng_() % 3);
    for (int e = 0; e < edits && bytes.size() > protect_; ++e) edit(bytes);
    return bytes;
  }

 private:
  std::size_t anywhere(const std::string& bytes) { return protect_ + rng_() % (bytes.size() - protect_); }

  void edit(std::string& bytes) {
    static const std::uint32_t words[] = {0u, 0xFFFFFFFFu, 0x7FFFFFFFu, 0x80000000u,
                                          0x7FC00000u /* NaN */, 0x7F800000u /* inf */, 0x7F7FFFFFu /* FLT_MAX */};
    const std::size_t at = anywhere(bytes);
    switch (rng_() % 5) {
      case 0:
        bytes[at] = static_cast<char>(bytes[at] ^ (1 << (rng_() % 8)));
        break;
      case 1: {
        const std::uint32_t word = words[rng_() % std::size(words)];
        for (std::size_t k = 0; k < 4 && at + k < bytes.size(); ++k)
          bytes[at + k] = static_cast<char>((word >> (8 * k)) & 0xFF);
        break;
      }
      case 2:
        bytes.erase(at, 1 + rng_() % 8);
        break;
      case 3:
        bytes.insert(at, bytes.substr(at, 1 + rng_() % 8));
        break;
      default:
        bytes.resize(at);
        break;
    }
  }

  std::mt19937 rng_;
  std::size_t protect_;
};

/// What a sweep saw: inputs the reader read (and whose result held its
/// promises) and inputs it refused with InputError.
struct SweepTally {
  int read = 0;
  int refused = 0;
};

/// What a refusal's message must name: the file, or the file and a line
/// ("<file>:<line>:", for line-oriented text formats).
enum class Naming { file, file_and_line };

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

/// Whether `message` names `path` as `naming` asks.
inline bool names_input(const std::string& message, const std::string& path, Naming naming) {
  const std::size_t at = message.find(path);
  if (at == std::string::npos) return false;
  if (naming == Naming::file) return true;
  std::size_t k = at + path.size();
  if (k >= message.size() || message[k] != ':') return false;
  const std::size_t digits = ++k;
  while (k < message.size() && std::isdigit(static_cast<unsigned char>(message[k]))) ++k;
  return k > digits && k < message.size() && message[k] == ':';
}

/// Writes each of `count` mutations of `valid` to `dir`/mutated`suffix` and
/// calls `read(path, input)`, which reads it and asserts what the reader
/// promises of a result. A refusal must be an InputError whose message
/// names the input as `naming` asks; any other exception or a failed
/// assertion fails the test and keeps the input as `dir`/failed-<k>`suffix`
/// for replay (a fatal failure ends the sweep).
template <class Mutator, class Read>
SweepTally sweep_reader(const std::filesystem::path& dir, const std::string& suffix, const std::string& valid,
                        Mutator mutate, int count, Naming naming, Read read) {
  SweepTally tally;
  const std::filesystem::path path = dir / ("mutated" + suffix);
  for (int k = 0; k < count; ++k) {
    const std::string input = mutate(valid);
    write_bytes(path, input);
    const auto keep = [&] { write_bytes(dir / ("failed-" + std::to_string(k) + suffix), input); };
    try {
      read(path.string(), input);
      if (::testing::Test::HasFatalFailure()) {
        keep();
        return tally;
      }
      ++tally.read;
    } catch (const InputError& error) {
      if (!names_input(error.what(), path.string(), naming)) {
        keep();
        ADD_FAILURE() << "mutation " << k << ": the message does not name the "
                      << (naming == Naming::file ? "file" : "file and line") << ": " << error.what();
      }
      ++tally.refused;
    } catch (const std::exception& error) {
      keep();
      ADD_FAILURE() << "mutation " << k << ": " << typeid(error).name() << " instead of InputError: " << error.what();
    }
  }
  return tally;
}

}  // namespace mrcloth::test
