#include "zoo/zoo.h"
#include <stdexcept>
namespace kintsugi::zoo {
ZooModel paper_object(int, bool) { throw std::logic_error("not yet"); }
ZooModel family(std::size_t, double, std::uint64_t) { throw std::logic_error("not yet"); }
}
