// kintsugi: repair the topology of reverse-engineered B-rep models.
#include "apps/bounded_read.h"
#include "apps/commands.h"

#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using namespace kintsugi::cli;
  // STEP and BREP files are read in a child process bounded in time and memory
  // (apps/bounded_read.h): a hostile file costs an error, not a hang.
  std::string error;
  auto bounds = read_bounds_from_environment(&error);
  if (!bounds) {
    std::cerr << "kintsugi: " << error << "\n";
    return kExitBadInput;
  }
  bound_cad_reads(*bounds);
  return run_kintsugi(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
}
