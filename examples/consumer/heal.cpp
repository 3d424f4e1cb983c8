// heal IN OUT: beautify a model with kintsugi's library (apps/api.h) and say what changed.
#include <apps/api.h>
#include <kernel/builders.h>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: heal IN OUT\n";
    return 2;
  }
  try {
    kintsugi::api::Model model = kintsugi::api::read_model(argv[1]);
    nlohmann::json report = kintsugi::api::beautify(model);
    kintsugi::api::write_model(model, argv[2], argv[1]);
    std::cout << "faces " << report["counts_before"]["faces"] << " -> " << report["counts_after"]["faces"] << ", "
              << kintsugi::api::repaired_count(report) << " repaired, " << kintsugi::api::not_repaired_count(report)
              << " not repaired\n";
    // The kernel is there too: a box built directly has six faces.
    std::cout << "a built box has " << kintsugi::build::box(1, 2, 3).counts().faces << " faces\n";
  } catch (const kintsugi::api::Error& e) {
    std::cerr << "heal: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
