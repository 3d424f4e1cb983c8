// Batch inputs, the manifest and its summary (apps/batch.h).
#include "apps/batch.h"

#include "io/native_json.h"
#include "problems/problem_type.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace kintsugi::cli::batch {

namespace {

bool is_model_file(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e == ".step" || e == ".stp" || e == ".iges" || e == ".igs" || e == ".brep" || e == ".json";
}

const char* const kStatuses[] = {"repaired", "partly_repaired", "unchanged", "failed", "timeout", "crashed"};

bool is_failure(const std::string& status) { return status == "failed" || status == "timeout" || status == "crashed"; }

}  // namespace

std::vector<std::string> find_inputs(const fs::path& in_dir, std::string* error) {
  std::vector<std::string> found;
  std::error_code ec;
  if (!fs::is_directory(in_dir, ec)) {
    *error = in_dir.string() + ": not a folder";
    return {};
  }
  fs::recursive_directory_iterator it(in_dir, fs::directory_options::skip_permission_denied, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    if (!it->is_regular_file(ec) || !is_model_file(it->path())) continue;
    found.push_back(it->path().lexically_relative(in_dir).generic_string());
  }
  if (ec) {
    *error = in_dir.string() + ": cannot list: " + ec.message();
    return {};
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::optional<std::uint64_t> parse_size(const std::string& s) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (...) {
    return std::nullopt;
  }
  std::string unit = s.substr(used);
  if (!unit.empty() && unit.back() == 'B') unit.pop_back();                  // "MB", "GiB"
  if (unit.size() == 2 && unit[1] == 'i') unit.pop_back();
  double scale = 1;
  if (unit == "K" || unit == "k") scale = 1024.0;
  else if (unit == "M" || unit == "m") scale = 1024.0 * 1024;
  else if (unit == "G" || unit == "g") scale = 1024.0 * 1024 * 1024;
  else if (unit == "T" || unit == "t") scale = 1024.0 * 1024 * 1024 * 1024;
  else if (!unit.empty()) return std::nullopt;
  const double bytes = v * scale;
  if (!std::isfinite(bytes) || bytes < 1 || bytes > 1e18) return std::nullopt;
  return std::uint64_t(bytes);
}

std::set<std::string> recorded_inputs(const fs::path& manifest, bool drop_torn_tail, std::string* error) {
  std::set<std::string> done;
  std::ifstream f(manifest, std::ios::binary);
  if (!f) return done;  // no manifest yet: nothing recorded
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  std::size_t complete = text.rfind('\n');
  complete = complete == std::string::npos ? 0 : complete + 1;
  if (complete < text.size() && drop_torn_tail) {
    std::error_code ec;
    fs::resize_file(manifest, complete, ec);
    if (ec) {
      *error = manifest.string() + ": cannot cut the torn last line: " + ec.message();
      return {};
    }
  }
  std::istringstream lines(text.substr(0, complete));
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (line.empty()) continue;
    auto j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("input") || !j["input"].is_string()) {
      *error = manifest.string() + ":" + std::to_string(number) + ": not a manifest line";
      return {};
    }
    done.insert(j["input"].get<std::string>());
  }
  return done;
}

fs::path summary_path_for(const fs::path& manifest) {
  std::string name = manifest.filename().string();
  if (name.size() > 6 && name.substr(name.size() - 6) == ".jsonl") name.resize(name.size() - 6);
  return manifest.parent_path() / (name + "-summary.json");
}

Summary finish_run(const fs::path& manifest, double wall_seconds, int jobs, std::size_t files_this_run, std::string* error) {
  Summary s;
  nlohmann::json by_status = nlohmann::json::object();
  for (const char* st : kStatuses) by_status[st] = 0;
  std::array<long long, 11> before{}, after{};
  nlohmann::json failures = nlohmann::json::array();
  double file_seconds = 0;
  long long files = 0;
  std::ifstream f(manifest);
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty()) continue;
    auto j = nlohmann::json::parse(line, nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("status")) {
      *error = manifest.string() + ": a line is not a manifest entry";
      s.exit_code = 2;
      return s;
    }
    ++files;
    const std::string status = j["status"].get<std::string>();
    by_status[status] = by_status.value(status, 0) + 1;
    if (j.value("seconds", nlohmann::json()).is_number()) file_seconds += j["seconds"].get<double>();
    if (is_failure(status)) failures.push_back({{"input", j["input"]}, {"status", status}, {"error", j["error"]}});
    for (ProblemType t : kAllProblemTypes) {
      const std::size_t i = std::size_t(problem_order(t) - 1);
      if (j["problems_before"].is_object()) before[i] += j["problems_before"].value(problem_name(t), 0);
      if (j["problems_after"].is_object()) after[i] += j["problems_after"].value(problem_name(t), 0);
    }
  }
  nlohmann::json pb = nlohmann::json::object(), pa = nlohmann::json::object();
  for (ProblemType t : kAllProblemTypes) {
    pb[problem_name(t)] = before[std::size_t(problem_order(t) - 1)];
    pa[problem_name(t)] = after[std::size_t(problem_order(t) - 1)];
  }
  s.exit_code = failures.empty() ? 0 : 3;
  s.json = {{"manifest", manifest.string()},
            {"files", files},
            {"status", by_status},
            {"problems_before", pb},
            {"problems_after", pa},
            {"failures", failures},
            {"seconds_in_children", file_seconds},
            {"wall_seconds_this_run", wall_seconds},
            {"files_this_run", files_this_run},
            {"files_per_second_this_run", wall_seconds > 0 ? double(files_this_run) / wall_seconds : 0.0},
            {"jobs", jobs}};

  std::ostringstream t;
  t << std::left << std::setw(22) << "status" << std::right << std::setw(8) << "files" << "\n";
  for (const char* st : kStatuses) t << std::left << std::setw(22) << st << std::right << std::setw(8) << by_status[st].get<long long>() << "\n";
  t << std::left << std::setw(22) << "total" << std::right << std::setw(8) << files << "\n";
  bool any = false;
  for (ProblemType t2 : kAllProblemTypes) {
    const std::size_t i = std::size_t(problem_order(t2) - 1);
    if (before[i] == 0 && after[i] == 0) continue;
    if (!any) t << "\n" << std::left << std::setw(22) << "problem" << std::right << std::setw(8) << "before" << std::setw(8) << "after" << "\n";
    any = true;
    t << std::left << std::setw(22) << problem_name(t2) << std::right << std::setw(8) << before[i] << std::setw(8) << after[i] << "\n";
  }
  // The first failures by name (all of them are in the manifest and the summary file).
  constexpr std::size_t kListed = 20;
  for (std::size_t i = 0; i < failures.size() && i < kListed; ++i) {
    const auto& fl = failures[i];
    t << (i == 0 ? "\n" : "") << fl["status"].get<std::string>() << ": " << fl["input"].get<std::string>() << ": "
      << (fl["error"].is_string() ? fl["error"].get<std::string>() : std::string()) << "\n";
  }
  if (failures.size() > kListed) t << "... and " << failures.size() - kListed << " more in " << manifest.string() << "\n";
  const fs::path summary_file = summary_path_for(manifest);
  t << "\n" << files_this_run << " file(s) in " << std::fixed << std::setprecision(1) << wall_seconds << " s ("
    << s.json["files_per_second_this_run"].get<double>() << " files/s, " << jobs << " job(s)); manifest "
    << manifest.string() << ", summary " << summary_file.string() << "\n";
  s.table = t.str();
  (void)io::write_file_atomically(summary_file.string(), s.json.dump(2) + "\n", error);
  return s;
}

}  // namespace kintsugi::cli::batch
