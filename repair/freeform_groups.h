// Work over a body's faces on several threads when some lie on free-form surfaces.
//
// A projection onto a free-form surface starts from the last one's foot on that surface
// (the backend keeps one evaluation state per surface, shared by the copies of its data
// and not thread-safe), so the faces sharing one surface's state go to one thread, in
// face order: what each face's measure sees does not depend on the threads. The
// free-form geometry's caches are built first, on the calling thread (they are made on
// first use, which is not thread-safe).
#pragma once

#include "kernel/body.h"

#include <functional>
#include <vector>

namespace kintsugi {

// The faces grouped by free-form evaluation state, each group in the order of `faces`;
// a face on an analytic surface is a group of its own.
std::vector<std::vector<FaceH>> evaluation_groups(const Body& b, const std::vector<FaceH>& faces);

// Builds the free-form caches of the faces' surfaces and of their edges' curves.
void prepare_freeform(const Body& b, const std::vector<FaceH>& faces);

// work(f) for every face of every group: each group on one thread, the groups shared out
// over `threads` threads (this one among them).
void for_each_grouped(const std::vector<std::vector<FaceH>>& groups, int threads, const std::function<void(FaceH)>& work);

}  // namespace kintsugi
