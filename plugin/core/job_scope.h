#pragma once
// A plugin's long operation announced to the host as a job for as long as
// a JobScope lives, so that a job whose slot throws is still reported finished.
#include "plugin/interfaces/process_interface.h"

#include <QString>

#include <utility>

namespace mrcloth {

class JobScope {
 public:
  /// `process`: the plugin; `id`: the job's name in progress lines; `steps`: its length.
  JobScope(ProcessInterface& process, QString id, const QString& description, int steps = 1)
      : process_(process), id_(std::move(id)), steps_(steps) {
    process_.startJob(id_, description, 0, steps_);
  }
  ~JobScope() { process_.finishJob(id_); }
  void progress(int steps_done) { process_.setJobState(id_, steps_done); }
  void done() { process_.setJobState(id_, steps_); }
  JobScope(const JobScope&) = delete;
  JobScope& operator=(const JobScope&) = delete;

 private:
  ProcessInterface& process_;
  QString id_;
  int steps_;
};

}  // namespace mrcloth
