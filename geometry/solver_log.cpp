#include "geometry/solver_log.h"

#include <glog/logging.h>

#include <mutex>

namespace kintsugi::geo {

void quiet_solver_log() {
  static std::once_flag once;
  std::call_once(once, [] { FLAGS_minloglevel = google::GLOG_FATAL; });
}

}  // namespace kintsugi::geo
