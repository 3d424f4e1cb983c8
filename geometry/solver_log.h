// Ceres reports through glog, and a few of its messages ignore
// Solver::Options::logging_type = SILENT (a solve that stops after five invalid steps
// logs an error, after glog's own "Logging before InitGoogleLogging()" warning). A
// failed solve is an answer we handle, not something to print on a user's terminal:
// quiet_solver_log() raises glog's threshold to FATAL once per process. Called before
// each solve; cheap after the first call.
#pragma once

namespace kintsugi::geo {

void quiet_solver_log();

}  // namespace kintsugi::geo
