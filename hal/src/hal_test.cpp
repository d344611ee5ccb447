#include "hal/hal_test.h"

#include <poll.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "hal/devices.h"
#include "hal/mock.h"
#include "hal/self_check.h"

namespace hal {

namespace {

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

double seconds(Nanos t) {
  return std::chrono::duration<double>(t).count();
}

}  // namespace

int run_hal_test(const HalTestOptions& options, std::ostream& out) {
  Backend backend;
  std::string why;
  if (options.backend.empty()) {
    backend = options.board_file.empty() ? Backend::mock : Backend::linux_kernel;
    why = options.board_file.empty() ? "no --board: the built-in mock board"
                                     : "--board without --hal; --hal mock simulates the board";
  } else if (parse_backend(options.backend, backend)) {
    why = "--hal " + options.backend;
  } else {
    out << "hal-test: --hal: expected 'linux' or 'mock', got '" << options.backend << "'\n";
    return 1;
  }
  out << "backend: " << to_string(backend) << " (" << why << ")\n";

  MonotonicClock clock;
  BoardConfig board;
  Devices dev;
  try {
    board = options.board_file.empty() ? builtin_mock_board() : load_board(options.board_file);
    dev = open_devices(board, backend, clock);
    if (options.board_file.empty() && backend == Backend::mock) {
      std::vector<MockButtonSpec> specs;
      for (const auto& b : board.buttons) specs.push_back({b.name, b.timing});
      auto buttons = std::make_unique<MockButtons>(specs, parse_button_script(kBuiltinScript, "<built-in script>"), clock);
      dev.mock_buttons = buttons.get();
      dev.buttons = std::move(buttons);
    }
  } catch (const ConfigError& e) {
    out << "hal-test: " << e.what() << "\n";
    return 1;
  }

  out << "board: " << (board.name.empty() ? board.source : board.name) << "\n";
  for (std::size_t i = 0; i < dev.buttons->count(); ++i) out << "  button " << dev.buttons->name(i) << "\n";
  for (std::size_t i = 0; i < dev.status->led_count(); ++i) out << "  led " << dev.status->led_name(i) << "\n";
  for (const auto& p : dev.problems) out << "  MISSING: " << p << "\n";
  out << "listening to buttons for " << options.duration_s << " s, cycling LEDs\n" << std::flush;

  // Each step lights one LED in one pattern for a full period of the slowest pattern, so a slow
  // blink or a heartbeat is seen whole and each LED can be told from the others.
  constexpr std::array kPatterns{LedPattern::on, LedPattern::blink_slow, LedPattern::blink_fast, LedPattern::heartbeat};
  Nanos step_len = std::chrono::milliseconds(500);
  for (LedPattern p : kPatterns)
    if (pattern_period(p) != Nanos::max()) step_len = std::max(step_len, pattern_period(p));
  const std::size_t leds = dev.status->led_count();
  const std::size_t steps = leds * kPatterns.size();
  const Nanos start = clock.now();
  const Nanos end = start + std::chrono::duration_cast<Nanos>(std::chrono::duration<double>(options.duration_s));
  std::size_t step = 0;
  Nanos next_step = leds > 0 ? start : Nanos::max();  // no LEDs: nothing to wake for but buttons
  std::array<ButtonEvent, 16> events;
  int event_count = 0;
  for (Nanos now = clock.now(); now < end; now = clock.now()) {
    if (now >= next_step) {
      const std::size_t led = step % leds;
      const LedPattern p = kPatterns[(step / leds) % kPatterns.size()];
      for (std::size_t i = 0; i < leds; ++i) dev.status->set_pattern(i, i == led ? p : LedPattern::off);
      out << "[" << seconds(now - start) << " s] led " << dev.status->led_name(led) << " -> " << to_string(p) << "\n";
      ++step;
      next_step = now + step_len;
      continue;
    }
    std::array<pollfd, 2> fds{{{dev.buttons->fd(), POLLIN, 0}, {dev.status->fd(), POLLIN, 0}}};
    // Rounded up, so the loop wakes at or after the deadline rather than spinning just before it.
    const Nanos wait = std::min(end, next_step) - now;
    const auto ms = std::chrono::ceil<std::chrono::milliseconds>(wait).count();
    poll(fds.data(), fds.size(), static_cast<int>(std::min<long long>(ms, 60'000)));
    if (fds[1].revents & POLLIN) dev.status->update();
    for (std::size_t n; (n = dev.buttons->read(events)) > 0;) {
      for (std::size_t i = 0; i < n; ++i, ++event_count)
        out << "[" << seconds(events[i].time - start) << " s] button " << dev.buttons->name(events[i].button) << " "
            << to_string(events[i].action) << "\n";
    }
  }
  for (std::size_t i = 0; i < leds; ++i) dev.status->set_pattern(i, LedPattern::off);
  out << event_count << " button events\n";
  if (leds > 0 && step < steps) {
    const double needed = seconds(step_len) * static_cast<double>(steps);
    out << "leds: showed " << step << " of " << steps << " LED patterns; --duration " << std::ceil(needed) << " shows them all\n";
  }

  StatusReport report;
  report.state = "hal-test";
  report.errors = dev.problems;
  bool ok = dev.problems.empty();
  // Failures while running: a line whose chip went away, an LED that could not be driven.
  for (const std::string* e : {&dev.buttons->last_error(), &dev.status->led_error()}) {
    if (e->empty()) continue;
    out << "FAILED: " << *e << "\n";
    report.errors.push_back(*e);
    ok = false;
  }
  if (dev.buttons->dropped() > 0)
    out << "buttons: " << dev.buttons->dropped() << " events dropped (the loop did not read them in time)\n";
  if (!dev.camera) {
    out << "camera: none on this board\n";
  } else {
    // The synthetic mock camera films whatever it is shown: given a frame with check markers, the
    // self-check runs end to end. A real camera films the real display, which hal-test does not drive.
    RgbImage presented;
    FiducialLayout layout;
    auto* mock = dynamic_cast<MockCamera*>(dev.camera.get());
    if (mock && board.mock_camera_images.empty()) {
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
        report.self_check = CheckSummary{r.passed, r.score, r.reason, clock.now()};
        ok = ok && r.passed;
      } else if (mock) {
        out << "self-check: not run: the mock camera plays image files, not a frame hal-test presented\n";
      } else {
        out << "self-check: not run: it compares the capture with the frame on the display, and hal-test has no "
               "display output yet; look at the saved capture instead\n";
      }
    }
  }
  if (!dev.status->status_file().empty()) {
    std::string err;
    if (dev.status->write_report(report, &err))
      out << "status file: " << dev.status->status_file() << "\n";
    else {
      out << "status file: " << err << "\n";
      ok = false;
    }
  }
  out << (ok ? "hal-test: all devices present\n" : "hal-test: some devices missing or failing (see above)\n");
  return ok ? 0 : 2;
}

}  // namespace hal
