#pragma once
// Timer and epoll descriptors shared by the devices. Each device gives the app one fd; where a
// device has several sources (one per GPIO line plus a timer) they are gathered in an epoll set,
// which is itself pollable.
#include "base/unique_fd.h"
#include "hal/clock.h"

namespace hal::detail {

// CLOCK_MONOTONIC timerfd, non-blocking. Throws std::system_error at construction time only.
base::UniqueFd make_timer();
// Arms `fd` to fire at absolute monotonic time `at` (a time already past fires at once);
// Nanos::max() disarms it.
void arm_timer(int fd, Nanos at);
void drain(int fd);  // reads a timerfd counter so it stops being readable

base::UniqueFd make_epoll();
void epoll_watch(int epoll_fd, int fd);

}  // namespace hal::detail
