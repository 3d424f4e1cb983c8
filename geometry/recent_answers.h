// The last few answers of an expensive geometric question (an intersection, a pcurve),
// newest first, for the questions asked again soon after: a repair tried again, the
// validity gate writing the same edges for the next repair. Few enough that a linear
// search comparing keys by value (surfaces, curves) is cheaper than hashing them. Safe
// to share between threads.
#pragma once

#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>

namespace kintsugi::geo {

template <class Entry, std::size_t Capacity>
class RecentAnswers {
 public:
  // answer(e) of the newest entry e for which is_it(e) holds.
  template <class Match, class Answer>
  auto find(Match is_it, Answer answer) -> std::optional<decltype(answer(std::declval<const Entry&>()))> {
    std::lock_guard<std::mutex> lock(m_);
    for (const Entry& e : entries_)
      if (is_it(e)) return answer(e);
    return std::nullopt;
  }
  void remember(Entry e) {
    std::lock_guard<std::mutex> lock(m_);
    entries_.push_front(std::move(e));
    if (entries_.size() > Capacity) entries_.pop_back();
  }

 private:
  std::mutex m_;
  std::deque<Entry> entries_;
};

}  // namespace kintsugi::geo
