// OpenCASCADE's messages: kept off our stdout, and BRepCheck's statuses by name.
#pragma once

#include <BRepCheck_Status.hxx>

#include <string>

namespace kintsugi::io::occt {

// Removes OpenCASCADE's default printers (translation chatter on stdout), once per
// process; the CLI's output is ours.
void silence_occt();

// The status as BRepCheck::Print names it ("Self Intersection Wire", ...), without the
// trailing newline.
std::string status_name(BRepCheck_Status s);

}  // namespace kintsugi::io::occt
