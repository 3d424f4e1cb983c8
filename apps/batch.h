// `kintsugi batch`: beautify every model under a folder, each file in its own child
// process (`kintsugi batch-file`, a hidden verb), so that a crash, a hang or a memory
// blow-up in one file (inside OpenCASCADE's reader too) costs that file only. Shared by
// the CLI (apps/cmd_batch.cpp) and the Python package's Dask runner (python/), which
// therefore write the same manifest lines.
//
// The manifest (OUT_DIR/kintsugi-batch.jsonl) has one JSON object per file:
//   {"input", "output", "status", "problems_before", "problems_after", "tolerance",
//    "seconds", "error"}
// input/output are relative to IN_DIR/OUT_DIR (output null unless written); status is
//   repaired         some problems repaired and detect finds none left
//   partly_repaired  some repaired, some left
//   unchanged        nothing repaired (no problems, or every repair was rolled back)
//   failed           the file could not be read, beautified or written; or it ran out
//                    of memory under --max-memory
//   timeout          killed after --timeout seconds
//   crashed          the child died of a signal or exited without a result
// problems_* are detect's counts by type (null unless the file was processed).
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <sys/types.h>
#include <vector>

namespace kintsugi::cli::batch {

namespace fs = std::filesystem;

// Exit status of `kintsugi batch-file` when the model did not fit under --max-memory.
constexpr int kExitOutOfMemory = 4;

struct Limits {
  double timeout_seconds = 600;     // <= 0: none
  std::uint64_t max_memory = 0;     // bytes of address space (RLIMIT_AS); 0: none
};

struct Job {
  fs::path in_dir, out_dir;
  std::string input;                // relative to in_dir; the output has the same relative path
  std::optional<double> tol;        // --tol, else each file's meta.tolerance or the default
};

// Every .step/.stp/.brep/.json under `in_dir` (recursively, any case), relative, sorted.
std::vector<std::string> find_inputs(const fs::path& in_dir, std::string* error);

// "512M", "2G", "1.5GiB", "1048576" (bytes); K/M/G/T are powers of 1024.
std::optional<std::uint64_t> parse_size(const std::string& s);

// The inputs a manifest already records. With `drop_torn_tail`, a last line without its
// newline (the writer was killed mid-line) is cut off the file, so its file is redone.
std::set<std::string> recorded_inputs(const fs::path& manifest, bool drop_torn_tail, std::string* error);
// The summary file beside a manifest: X.jsonl -> X-summary.json.
fs::path summary_path_for(const fs::path& manifest);

// A child running one job.
struct Child {
  Job job;
  pid_t pid = -1;
  int pidfd = -1;                   // readable when the child exits (-1: poll instead)
  fs::path result, log;             // its result document and its stdout+stderr
  std::chrono::steady_clock::time_point start, deadline;
  bool killed_for_timeout = false;
};

// Starts `exe batch-file IN OUT RESULT [--tol T]` under `limits`; `scratch` is a private
// folder for the result and log files, `serial` makes their names unique in it.
Child spawn_child(const std::string& exe, const Job& job, const Limits& limits, const fs::path& scratch, long serial);
// Reaps the child if it has ended: returns its manifest entry, or nullopt if it runs on.
// Kills it (its whole process group) first when it is past its deadline.
std::optional<nlohmann::json> reap_child(Child& c, const Limits& limits);
void kill_child(Child& c);
// Runs one job to its end (spawn, wait, reap): the Dask runner's task.
nlohmann::json run_job(const std::string& exe, const Job& job, const Limits& limits);
// The path of the running program (for re-executing it as the child).
std::string self_exe();

// What `batch-file` does in the child: the whole result document it writes.
int run_batch_file(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// Totals over a whole manifest (resumed runs included), written beside it
// (summary_path_for) as {"files", "status": {status: n}, "problems_before",
// "problems_after", "failures": [...], "seconds_in_children", "wall_seconds_this_run",
// "files_this_run", "files_per_second_this_run", "jobs"}, and the table printed at the
// end. exit_code: 0, or 3 when some file failed, timed out or crashed.
struct Summary {
  nlohmann::json json;
  std::string table;
  int exit_code = 0;
};
Summary finish_run(const fs::path& manifest, double wall_seconds, int jobs, std::size_t files_this_run, std::string* error);

}  // namespace kintsugi::cli::batch
