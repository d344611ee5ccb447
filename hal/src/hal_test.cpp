#include "hal/hal_test.h"

#include <poll.h>

#include <array>
#include <cmath>

#include "hal/devices.h"
#include "hal/mock.h"
#include "hal/self_check.h"

namespace hal {

namespace {

// Used when no board file is given: what a Pi with three buttons and two LEDs would have.
constexpr const char* kBuiltinBoard = R"(
[board]
name = "built-in mock board"
[buttons]
debounce_ms = 20
long_press_ms = 600
[[button]]
name = "play"
line = "GPIO17"
[[button]]
name = "next"
line = "GPIO27"
repeat_delay_ms = 400
repeat_interval_ms = 100
[[button]]
name = "check"
line = "GPIO22"
[[led]]
name = "status"
line = "GPIO23"
[[led]]
name = "error"
line = "GPIO24"
[camera]
device = "/dev/v4l/by-id/mock-camera"
)";

// Bounce on "play", a long press on "check", a held "next" that auto-repeats.
constexpr const char* kBuiltinScript = R"(
100 play press
103 play release
105 play press
250 play release
300 next press
900 next release
950 check press
1700 check release
)";

double seconds(Nanos t) { return std::chrono::duration<double>(t).count(); }

}  // namespace

int run_hal_test(const HalTestOptions& options, std::ostream& out) {
  Backend backend;
  if (!parse_backend(options.backend, backend)) {
    out << "hal-test: --hal: expected 'linux' or 'mock', got '" << options.backend << "'\n";
    return 1;
  }
  MonotonicClock clock;
  BoardConfig board;
  Devices dev;
  try {
    board = options.board_file.empty() ? parse_board(kBuiltinBoard, "<built-in board>") : load_board(options.board_file);
    dev = open_devices(board, backend, clock);
    if (options.board_file.empty() && backend == Backend::Mock) {
      std::vector<MockButtonSpec> specs;
      for (const auto& b : board.buttons) specs.push_back({b.name, b.timing});
      dev.buttons = std::make_unique<MockButtons>(specs, parse_button_script(kBuiltinScript, "<built-in script>"), clock);
    }
  } catch (const ConfigError& e) {
    out << "hal-test: " << e.what() << "\n";
    return 1;
  }

  out << "board: " << (board.name.empty() ? board.source : board.name) << " (" << options.backend << ")\n";
  for (std::size_t i = 0; i < dev.buttons->count(); ++i) out << "  button " << dev.buttons->name(i) << "\n";
  for (std::size_t i = 0; i < dev.status->led_count(); ++i) out << "  led " << dev.status->led_name(i) << "\n";
  for (const auto& p : dev.problems) out << "  MISSING: " << p << "\n";
  out << "listening to buttons for " << options.duration_s << " s, cycling LEDs\n" << std::flush;

  constexpr std::array kPatterns{LedPattern::On, LedPattern::BlinkSlow, LedPattern::BlinkFast, LedPattern::Heartbeat};
  const Nanos start = clock.now();
  const Nanos end = start + std::chrono::duration_cast<Nanos>(std::chrono::duration<double>(options.duration_s));
  const Nanos step_len = std::chrono::milliseconds(700);
  std::size_t step = 0;
  Nanos next_step = start;
  std::array<ButtonEvent, 16> events;
  int event_count = 0;
  while (clock.now() < end) {
    if (dev.status->led_count() > 0 && clock.now() >= next_step) {
      const std::size_t led = step % dev.status->led_count();
      const LedPattern p = kPatterns[(step / dev.status->led_count()) % kPatterns.size()];
      for (std::size_t i = 0; i < dev.status->led_count(); ++i) dev.status->set_pattern(i, i == led ? p : LedPattern::Off);
      out << "[" << seconds(clock.now() - start) << " s] led " << dev.status->led_name(led) << " -> " << to_string(p)
          << "\n";
      ++step;
      next_step += step_len;
    }
    std::array<pollfd, 3> fds{{{dev.buttons->fd(), POLLIN, 0}, {dev.status->fd(), POLLIN, 0}, {-1, POLLIN, 0}}};
    const Nanos wait = std::min(end, next_step) - clock.now();
    poll(fds.data(), fds.size(), std::max(0, static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(wait).count()) + 1));
    if (fds[1].revents & POLLIN) dev.status->update();
    for (std::size_t n; (n = dev.buttons->read(events)) > 0;) {
      for (std::size_t i = 0; i < n; ++i, ++event_count)
        out << "[" << seconds(events[i].time - start) << " s] button " << dev.buttons->name(events[i].button) << " "
            << to_string(events[i].action) << "\n";
    }
  }
  for (std::size_t i = 0; i < dev.status->led_count(); ++i) dev.status->set_pattern(i, LedPattern::Off);
  out << event_count << " button events\n";

  StatusReport report;
  report.state = "hal-test";
  report.errors = dev.problems;
  bool ok = dev.problems.empty();
  if (!dev.camera) {
    out << "camera: none on this board\n";
  } else {
    // The mock camera looks at a synthetic frame with check markers, so the self-check runs end to end.
    RgbImage presented;
    FiducialLayout layout;
    if (auto* mock = dynamic_cast<MockCamera*>(dev.camera.get())) {
      presented = make_test_scene(640, 360, 1, 0.0);
      layout = FiducialLayout::for_display(presented.width, presented.height, 0);
      draw_fiducials(presented, layout);
      mock->show(presented);
    }
    RgbImage frame;
    if (!dev.camera->capture(frame, std::chrono::seconds(3))) {
      out << "camera: no frame within 3 s: "
          << (dev.camera->last_error().empty() ? std::string("timeout") : dev.camera->last_error()) << "\n";
      report.errors.push_back("camera: no frame");
      ok = false;
    } else {
      std::string err;
      if (save_image(options.capture_path, frame, &err)) {
        out << "camera: captured " << frame.width << "x" << frame.height << ", saved to " << options.capture_path << "\n";
      } else {
        out << "camera: " << err << "\n";
        ok = false;
      }
      if (!presented.empty()) {
        DisplayChecker checker;
        const SelfCheckResult r = checker.check(presented, layout, frame);
        out << "self-check: " << (r.passed ? "pass" : "FAIL") << " score " << r.score << " (" << r.reason << ")\n";
        report.last_check = CheckSummary{r.passed, r.score, r.reason, clock.now()};
        ok = ok && r.passed;
      }
    }
  }
  if (!dev.status->status_file().empty()) {
    std::string err;
    if (dev.status->write_report(report, &err)) out << "status file: " << dev.status->status_file() << "\n";
    else {
      out << "status file: " << err << "\n";
      ok = false;
    }
  }
  out << (ok ? "hal-test: all devices present\n" : "hal-test: some devices missing or failing (see above)\n");
  return ok ? 0 : 2;
}

}  // namespace hal
