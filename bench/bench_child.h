// What every kintsugi-bench mode shares: memory and time readings, and running one
// measurement in a child process of its own so that its peak memory is its own.
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>

namespace kintsugi::bench {

// The process's peak resident set size (getrusage), in bytes.
long long peak_rss_bytes();
// The resident set size now (/proc/self/statm), or -1.
long long current_rss_bytes();
double seconds_since(std::chrono::steady_clock::time_point t0);
// Runs `work` in a child process and returns the JSON it produced (plus its peak RSS as
// "peak_rss_bytes"), or {"error"} when it threw or the child failed.
nlohmann::ordered_json json_in_child(const std::function<nlohmann::ordered_json()>& work);

}  // namespace kintsugi::bench
