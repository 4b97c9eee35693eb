"use strict";
// The report of a finished `mrcloth pipeline` run, for the bench scripts
// that re-run its models (core.include("pipeline_report.js")): its
// report.json says what each test run was given and which mesh each model
// is, so the re-runs are the pipeline's own runs, not a copy of its rules.

/// Parsed <out>/report.json; throws naming the file when it is missing or
/// was written by a pipeline that did not record testSettings and modelFile.
function readPipelineReport(out) {
  const reportPath = out + "/report.json";
  if (!core.fileReadable(reportPath)) throw new Error(reportPath + " is not readable: expected a finished pipeline run");
  const report = JSON.parse(core.readTextFile(reportPath));
  if (!report.testSettings || !report.table3.every((row) => row.modelFile))
    throw new Error(reportPath + " has no testSettings or modelFile: expected a report from a pipeline that records " +
                    "them (re-run the pipeline)");
  return report;
}
