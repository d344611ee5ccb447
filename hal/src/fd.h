#pragma once
// Timer and epoll descriptors shared by the devices. Each device gives the app one fd; where a
// device has several sources (one per GPIO line plus a timer) they are gathered in an epoll set,
// which is itself pollable.
#include <string>

#include "hal/clock.h"
#include "hal/unique_fd.h"

namespace hal::detail {

// CLOCK_MONOTONIC timerfd, non-blocking. Throws std::system_error at construction time only.
UniqueFd make_timer();
// Arms `fd` to fire at absolute monotonic time `at` (a time already past fires at once);
// Nanos::max() disarms it.
void arm_timer(int fd, Nanos at);
void drain(int fd);  // reads a timerfd counter so it stops being readable

UniqueFd make_epoll();
void epoll_watch(int epoll_fd, int fd);

std::string errno_text(int err);

}  // namespace hal::detail
