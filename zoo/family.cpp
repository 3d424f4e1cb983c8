#include "zoo/zoo.h"
#include <stdexcept>
namespace kintsugi::zoo {
ZooModel family(std::size_t, double, std::uint64_t) { throw std::invalid_argument("the family is not built yet"); }
}
