#pragma once
// `player hal-test`: the wiring check an installer runs on a new board.
#include <ostream>
#include <string>

namespace hal {

struct HalTestOptions {
  std::string board_file;                            // empty: a built-in mock board
  std::string backend = "mock";                      // "linux" or "mock"
  std::string capture_path = "hal-test-capture.png"; // where the captured frame is saved
  double duration_s = 10.0;                          // how long to listen to buttons and cycle LEDs
};

// Prints button events as they come, cycles every LED through every pattern, captures one frame and
// saves it, writes a status file if the board names one, and on the mock backend also runs the
// display self-check on a synthetic frame. Returns 0 when everything on the board worked, 1 for a
// bad board file or option, 2 when some device was missing or failed (details printed).
int run_hal_test(const HalTestOptions& options, std::ostream& out);

}  // namespace hal
