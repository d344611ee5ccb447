#pragma once
// Reading events from a real Buttons backend in the hardware tests (linux_test, keyboard_test).
#include <poll.h>

#include <array>
#include <chrono>
#include <string>
#include <vector>

#include "hal/buttons.h"

namespace hal::test {

// Reads button events until `n` have come or `guard` has passed (a guard against a hang, not a
// timing check).
inline std::vector<ButtonEvent> wait_events(Buttons& b, std::size_t n,
                                            std::chrono::milliseconds guard = std::chrono::seconds(10)) {
  std::vector<ButtonEvent> got;
  const auto end = std::chrono::steady_clock::now() + guard;
  while (got.size() < n && std::chrono::steady_clock::now() < end) {
    pollfd p{b.fd(), POLLIN, 0};
    poll(&p, 1, 50);
    std::array<ButtonEvent, 8> ev;
    const std::size_t k = b.read(ev);
    got.insert(got.end(), ev.begin(), ev.begin() + static_cast<std::ptrdiff_t>(k));
  }
  return got;
}

// "[next Press, next Release]", for failure messages.
inline std::string describe(const std::vector<ButtonEvent>& events, const Buttons& b) {
  std::string s;
  for (const ButtonEvent& e : events)
    s += (s.empty() ? "" : ", ") + std::string(b.name(e.button)) + " " + std::string(to_string(e.action));
  return "[" + s + "]";
}

}  // namespace hal::test
