#pragma once
// `player hal-test`: the wiring check an installer runs on a new board.
#include <ostream>
#include <string>

namespace hal {

struct HalTestOptions {
  std::string board_file;  // empty: a built-in mock board
  // "linux", "mock", or empty: linux when a board file is given (checking a real board is what
  // hal-test is for, and mocks would report every device present), else mock.
  std::string backend;
  std::string capture_path = "hal-test-capture.png";  // where the captured frame is saved
  double duration_s = 10.0;                           // how long to listen to buttons and cycle LEDs
};

// Prints the backend in use (and why) on the first line, then button events as they come; shows
// each LED each pattern in turn, for a full period of the slowest pattern; captures one frame and
// saves it; writes a status file if the board names one. The display self-check runs only on the
// mock backend's synthetic camera, which films a frame hal-test presents: on linux hal-test has no
// display output (the kms platform is not built), so there is no presented frame to compare with.
// Returns 0 when everything on the board worked, 1 for a bad board file or option, 2 when some
// device was missing or failed (details printed).
int run_hal_test(const HalTestOptions& options, std::ostream& out);

}  // namespace hal
