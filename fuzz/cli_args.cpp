// The whole command line (apps/dispatch.cpp's run_kintsugi, what `kintsugi` runs) on
// random argument lists drawn from the verbs, their options, edge-case values and paths
// in a private scratch folder holding two input files. What must hold:
//   - no crash, no sanitizer report, an exit code of 0, 1 or 2;
//   - a refusal (exit 2) says why on stderr and leaves no new file behind;
//   - a file the command reads is never written to (one named only as its output may
//     be), and no temporary file is left behind.
// Not fuzzed here: demo and audit (each runs for seconds to minutes whatever the
// arguments), batch (it re-executes the running program, here the fuzzer), batch-file
// (batch's internal child: it writes its result file where batch tells it), view --png
// (starts a browser). A violation aborts (the fuzzer reports it).
#include "apps/commands.h"
#include "fuzz/die.h"
#include "io/native_json.h"
#include "kernel/builders.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <sys/stat.h>

using namespace kintsugi;

using fuzz::die;
namespace fs = std::filesystem;

namespace {

struct Scratch {
  fs::path dir;
  std::map<fs::path, std::string> inputs;  // path -> its bytes
};

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

const Scratch& scratch() {
  static const Scratch s = [] {
    Scratch s;
    std::string tmpl = (fs::temp_directory_path() / "kintsugi-fuzz-cli-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) die("cannot make a scratch folder");
    s.dir = tmpl;
    // Words taken as output names (`-o box`) are relative paths: they land here, where
    // they are checked and removed, not in the folder the fuzzer was started from.
    fs::current_path(s.dir);
    std::string error;
    if (!io::write_native_file((s.dir / "in.json").string(), build::box(1, 2, 3), {{"tolerance", 0.01}}, "mm", &error))
      die(error);
    std::ofstream(s.dir / "bad.json") << R"({"format": "kintsugi-brep", "version": 1, "vertices": [)";
    for (const char* n : {"in.json", "bad.json"}) s.inputs[s.dir / n] = slurp(s.dir / n);
    return s;
  }();
  return s;
}

std::vector<std::string> tokens() {
  const fs::path d = scratch().dir;
  std::vector<std::string> t = {
      // verbs (see the header for those left out) and help
      "generate", "check", "inject", "detect", "beautify", "convert", "measure", "view", "--help", "-h", "help",
      // options of every verb
      "-o", "--tol", "--json", "--occt", "--type", "--seed", "--at", "--report", "--html", "--chordal", "--list",
      "--clean", "--sx", "--sy", "--sz", "--sides", "--radius", "--height", "--major", "--minor", "--faces", "--size",
      "--frob", "-", "--", "",
      // models and defect types
      "box", "prism", "pyramid", "cylinder", "torus", "sphere", "cone", "grid", "paper-1", "paper-11", "family",
      "short_edge", "small_face", "face_gap", "mergeable_edges", "crack", "v0", "e3", "f1", "l0", "f999",
      // values
      "0", "-1", "1", "3", "0.01", "1e-300", "1e308", "1e309", "-0", "nan", "inf", "-inf", "0x10", "2000000",
      "9223372036854775808", "1,5", " 1", "abc",
      // paths: the inputs, outputs of every type, a folder, a missing folder
      (d / "in.json").string(), (d / "bad.json").string(), (d / "missing.json").string(), (d / "out.json").string(),
      (d / "out.step").string(), (d / "out.brep").string(), (d / "out.obj").string(), (d / "page.html").string(),
      (d / "report.json").string(), d.string(), (d / "no" / "such" / "dir" / "out.json").string(),
      (d / "IN.JSON").string(), (d / "." / "in.json").string()};
  return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 24) return 0;
  static const std::vector<std::string> dict = tokens();
  const Scratch& s = scratch();
  // Each byte is a token: below 0xf0 from the list; from 0xf0 a number-like string of
  // up to 4 characters built from the next bytes (never a path: only digits . e - +).
  std::vector<std::string> args;
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] < 0xf0) {
      args.push_back(dict[data[i] % dict.size()]);
      continue;
    }
    std::string num;
    for (int k = 0; k < (data[i] & 3) + 1 && i + 1 < size; ++k) num += "0123456789.e-+"[data[++i] % 14];
    args.push_back(num);
  }
  for (const std::string& a : args)
    if (a == "--png" || a == "demo" || a == "audit" || a == "batch" || a == "batch-file") return 0;

  std::ostringstream out, err;
  const int code = cli::run_kintsugi(args, out, err);
  std::string cmd = "kintsugi";
  for (const std::string& a : args) cmd += " '" + a + "'";

  if (code != cli::kExitOk && code != cli::kExitInvalid && code != cli::kExitBadInput)
    die(cmd + ": exit code " + std::to_string(code));
  if (code == cli::kExitBadInput && err.str().empty()) die(cmd + ": exit 2 without a message");
  // A scratch file named only as an output (`generate torus -o in.json`: generate reads
  // nothing) may be written, as the user asked; a file the command also reads may not
  // (the CLI refuses an output that is its input). Written outputs are put back so that
  // later runs start from the same files.
  auto same = [](const fs::path& a, const std::string& b) {
    return a.lexically_normal() == fs::path(b).lexically_normal();
  };
  auto named_as_output_only = [&](const fs::path& path) {
    bool as_output = false, elsewhere = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
      if (!same(path, args[i])) continue;
      const bool after_option = i > 0 && (args[i - 1] == "-o" || args[i - 1] == "--report" || args[i - 1] == "--html");
      const bool convert_target = !args.empty() && args[0] == "convert" && i + 1 == args.size() && i >= 2;
      (after_option || convert_target ? as_output : elsewhere) = true;
    }
    return as_output && !elsewhere;
  };
  // Written means new bytes or a new file in its place (an atomic write of the same
  // bytes renames a new inode over it: the bytes alone would not show it).
  static std::map<fs::path, std::pair<ino_t, std::int64_t>> stamp;
  auto stamp_of = [](const fs::path& p) {
    struct stat st {};
    ::stat(p.c_str(), &st);
    return std::pair(st.st_ino, std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec);
  };
  for (const auto& [path, bytes] : s.inputs) {
    if (!stamp.count(path)) stamp[path] = stamp_of(path);
    if (slurp(path) != bytes || stamp_of(path) != stamp[path]) {
      if (code != cli::kExitOk || !named_as_output_only(path)) die(cmd + ": wrote to the input " + path.string());
      std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
      stamp[path] = stamp_of(path);
    }
  }
  std::vector<fs::path> made;
  for (const auto& e : fs::directory_iterator(s.dir))
    if (!s.inputs.count(e.path())) made.push_back(e.path());
  for (const fs::path& p : made) {
    const std::string n = p.filename().string();
    if (n.find(".tmp") != std::string::npos) die(cmd + ": left a temporary file " + n);
    if (code == cli::kExitBadInput) die(cmd + ": refused (exit 2: " + err.str() + ") but wrote " + n);
    std::error_code ec;
    fs::remove_all(p, ec);
  }
  return 0;
}
