# Sourced by the interruption tests: waiting for a background host.

# wait_for_line <file> <grep pattern> <pid> <what>: returns once the file has
# a line matching the pattern (at most 60 s); else prints "<what> did not
# start" and the file, kills the process and exits 1.
wait_for_line() {
  tries=0
  until grep -q "$2" "$1" 2>/dev/null; do
    tries=$((tries + 1))
    if [ "$tries" -gt 600 ] || ! kill -0 "$3" 2>/dev/null; then
      echo "$4 did not start"; cat "$1"; kill "$3" 2>/dev/null; exit 1
    fi
    sleep 0.1
  done
}

# interrupt_and_wait <pid>: sends SIGINT and waits; sets `code` (the exit
# status) and `elapsed_ms` (from the signal to the exit).
interrupt_and_wait() {
  start=$(date +%s%N)
  kill -INT "$1"
  wait "$1"
  code=$?
  elapsed_ms=$(( ($(date +%s%N) - start) / 1000000 ))
}
