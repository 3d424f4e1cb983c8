// The STEP and BREP readers (io::import_cad, what `kintsugi` reads .step/.stp/.brep
// with) on mutated files. An input starting with "ISO-10303-21" is read as STEP, any
// other as BREP. What must hold: a refusal comes with a message that names the file; a
// body that is read passes check_topology. A violation aborts (the fuzzer reports it).
//
// The CLI reads these files in a child process bounded in time and memory
// (apps/bounded_read.h); here the reader runs in-process, so that libFuzzer sees its
// coverage, and libFuzzer's own -timeout and -rss_limit_mb are the bounds: a hang or a
// huge allocation is a finding.
//
// Besides libFuzzer's byte mutations, a custom mutator changes a STEP file's structure:
// it deletes or duplicates an entity line, points a reference (#n) at another entity,
// or replaces a number with an extreme one.
#include "fuzz/die.h"
#include "invariants/topology_check.h"
#include "io/occt/exchange.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <string_view>
#include <unistd.h>
#include <vector>

using namespace kintsugi;

using fuzz::die;

namespace {

std::string scratch_path(bool step) {
  return (std::filesystem::temp_directory_path() /
          ("kintsugi-fuzz-" + std::to_string(::getpid()) + (step ? ".step" : ".brep")))
      .string();
}

// The entity instances ("#12 = ...;", possibly over several lines): [begin, end) of
// each, the ';' and the line break after it included.
std::vector<std::pair<std::size_t, std::size_t>> entities_of(const std::string& s) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t b = s.find("\n#"); b != std::string::npos; b = s.find("\n#", b)) {
    std::size_t e = s.find(';', b);
    if (e == std::string::npos) break;
    e = std::min(s.size(), e + 2);
    out.emplace_back(b + 1, e);
    b = e - 1;
  }
  return out;
}

// One structural change to the text; false if none applied.
bool mutate_structure(std::string& s, std::mt19937& rng) {
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  // Entities only: the header stays, so the file is still read as STEP.
  const auto entities = entities_of(s);
  if (entities.empty()) return false;
  auto [b, e] = entities[pick(entities.size())];
  switch (pick(4)) {
    case 0: s.erase(b, e - b); return true;                      // a missing entity
    case 1: s.insert(e, s.substr(b, e - b)); return true;        // a duplicated id
    case 2: {                                                    // a reference elsewhere
      std::vector<std::size_t> refs;
      for (std::size_t i = s.find('#', b + 1); i < e; i = s.find('#', i + 1)) refs.push_back(i);
      if (refs.empty()) return false;
      std::size_t at = refs[pick(refs.size())] + 1, end = at;
      while (end < s.size() && std::isdigit(static_cast<unsigned char>(s[end]))) ++end;
      static const char* kTargets[] = {"0", "1", "999999", "2147483648", "99999999999999999999"};
      std::string target = pick(2) ? kTargets[pick(5)] : std::to_string(1 + pick(entities.size() + 8));
      s.replace(at, end - at, target);
      return true;
    }
    default: {                                                   // an extreme number
      std::vector<std::size_t> nums;
      for (std::size_t i = b + 1; i < e; ++i)
        if ((std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '-') && s[i - 1] != '#' &&
            !std::isalnum(static_cast<unsigned char>(s[i - 1])) && s[i - 1] != '.')
          nums.push_back(i);
      if (nums.empty()) return false;
      std::size_t at = nums[pick(nums.size())], end = at + 1;
      while (end < e && (std::isdigit(static_cast<unsigned char>(s[end])) || s[end] == '.' || s[end] == 'E' ||
                         s[end] == 'e' || s[end] == '-' || s[end] == '+'))
        ++end;
      static const char* kNumbers[] = {"0.",      "-0.",    "1.E308", "-1.E308", "1.E-308", "1.E999",
                                       "4294967296", "-1",  "1.E+",   "99999999999999999999."};
      s.replace(at, end - at, kNumbers[pick(10)]);
      return true;
    }
  }
}

}  // namespace

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t max_size);

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t max_size,
                                               unsigned int seed) {
  std::mt19937 rng(seed);
  std::string s(reinterpret_cast<const char*>(data), size);
  if (rng() % 2 == 0 && s.rfind("ISO-10303-21", 0) == 0 && mutate_structure(s, rng) && s.size() <= max_size) {
    std::copy(s.begin(), s.end(), data);
    return s.size();
  }
  return LLVMFuzzerMutate(data, size, max_size);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const bool step = text.substr(0, 12) == "ISO-10303-21";
  const std::string path = scratch_path(step);
  {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(text.data(), std::streamsize(text.size()));
    if (!f) die("cannot write the scratch file " + path);
  }
  std::string error;
  auto imp = io::import_cad(path, step ? io::CadFormat::step : io::CadFormat::brep, &error);
  std::filesystem::remove(path);
  if (!imp) {
    if (error.rfind(path + ": ", 0) != 0) die("a refusal that does not name the file: '" + error + "'");
    return 0;
  }
  auto bad = check_topology(imp->body);
  if (!bad.empty()) die("read a body that breaks " + to_string(bad.front()));
  return 0;
}
