#include "playback/timeline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace playback {

namespace {

constexpr double min_duration_s = 1e-3;    // guards the arithmetic against hand-built playlists
constexpr double previous_window_s = 2.0;  // previous() within this of an item's start: the item before
constexpr double wall_jump_s = 0.25;       // a wall clock step larger than this within a slot is a cut

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Uniform in [0, bound) by rejection, so the order does not depend on the standard library's
// distributions (mt19937_64's output is fixed by the standard).
std::uint64_t below(std::mt19937_64& engine, std::uint64_t bound) {
  const std::uint64_t threshold = (0 - bound) % bound;
  for (;;) {
    const std::uint64_t r = engine();
    if (r >= threshold) return r % bound;
  }
}

// b > 0: every divisor here is a playlist's length.
std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return a - q * b < 0 ? q - 1 : q;
}

double wrap360(double a) {
  a = std::fmod(a, 360.0);
  if (a < 0) a += 360.0;
  return a >= 360.0 ? 0.0 : a;
}

// Catmull-Rom through the keys on one channel: non-uniform finite-difference tangents, zero at
// both ends; before the first key and after the last the value holds.
double spline(const std::vector<OrbitKey>& k, double t, double OrbitKey::*channel) {
  const std::size_t n = k.size();
  if (n == 1 || !(t > k[0].t)) return k[0].*channel;
  if (t >= k[n - 1].t) return k[n - 1].*channel;
  const auto it = std::upper_bound(k.begin(), k.end(), t, [](double v, const OrbitKey& key) { return v < key.t; });
  const std::size_t i = static_cast<std::size_t>(it - k.begin()) - 1;
  auto tangent = [&](std::size_t j) {
    if (j == 0 || j == n - 1) return 0.0;
    return (k[j + 1].*channel - k[j - 1].*channel) / (k[j + 1].t - k[j - 1].t);
  };
  const double h = k[i + 1].t - k[i].t, s = (t - k[i].t) / h, s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * (k[i].*channel) + (s3 - 2 * s2 + s) * h * tangent(i) + (-2 * s3 + 3 * s2) * (k[i + 1].*channel) +
         (s3 - s2) * h * tangent(i + 1);
}

// The spline may overshoot between keys; elevation and distance must stay valid.
double within_keys(const std::vector<OrbitKey>& k, double v, double OrbitKey::*channel) {
  const auto [lo, hi] =
      std::minmax_element(k.begin(), k.end(), [&](const OrbitKey& a, const OrbitKey& b) { return a.*channel < b.*channel; });
  return std::clamp(v, (*lo).*channel, (*hi).*channel);
}

}  // namespace

Camera camera_at(const CameraPath& path, double t) {
  Camera c{path.azimuth_deg, path.elevation_deg, path.distance, path.fov_deg};
  switch (path.motion) {
    case Motion::still:
      break;
    case Motion::file:
      c.file_index = path.index;
      break;
    case Motion::turntable:
      if (path.period_s > 0 && std::isfinite(t)) c.azimuth_deg += 360.0 * std::fmod(t, path.period_s) / path.period_s;
      break;
    case Motion::orbit:
      if (!path.keys.empty()) {
        c.azimuth_deg = spline(path.keys, t, &OrbitKey::azimuth_deg);
        c.elevation_deg = within_keys(path.keys, spline(path.keys, t, &OrbitKey::elevation_deg), &OrbitKey::elevation_deg);
        c.distance = within_keys(path.keys, spline(path.keys, t, &OrbitKey::distance), &OrbitKey::distance);
      }
      break;
  }
  c.azimuth_deg = wrap360(c.azimuth_deg);
  return c;
}

Timeline::Timeline(Playlist playlist, double now, double wall_now) {
  last_now_ = now;
  last_wall_ = wall_now;
  last_wall_mono_ = now;
  reset_playlist(std::move(playlist));
  if (mode_ == Mode::wallclock)
    run_wallclock(wall_now);
  else
    run_sequential();
}

void Timeline::reset_playlist(Playlist playlist) {
  playlist_ = std::move(playlist);
  const std::size_t n = playlist_.items.size();
  playable_.assign(n, 1);
  playable_count_ = static_cast<int>(n);
  slot_end_.resize(n);
  double end = 0;
  finite_cycle_ = 0;
  infinite_playable_ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = duration(static_cast<int>(i));
    slot_end_[i] = end += d;
    if (std::isfinite(d))
      finite_cycle_ += d;
    else
      ++infinite_playable_;
  }
  mode_ = playlist_.schedule == Schedule::wallclock ? Mode::wallclock : Mode::sequential;
  for (auto& c : cache_) c.pass = none;
  wall_valid_ = false;
}

void Timeline::advance_clock(double now) {
  if (!(now > last_now_)) return;  // also ignores NaN
  if (!paused_) play_time_ += now - last_now_;
  last_now_ = now;
}

bool Timeline::looping() const {
  return mode_ == Mode::local || playlist_.loop;
}
bool Timeline::shuffled() const {
  return mode_ == Mode::sequential && playlist_.shuffle;
}

double Timeline::playable_cycle() const {
  return infinite_playable_ > 0 ? std::numeric_limits<double>::infinity() : finite_cycle_;
}

double Timeline::duration(int item) const {
  const double d = playlist_.items[static_cast<std::size_t>(item)].duration_s;
  return d >= min_duration_s ? d : min_duration_s;
}

void Timeline::shuffle_pass(std::uint64_t pass, std::vector<int>& out) const {
  out.resize(playlist_.items.size());
  std::iota(out.begin(), out.end(), 0);
  std::mt19937_64 engine(splitmix64(playlist_.seed ^ splitmix64(pass)));
  for (std::size_t i = out.size(); i > 1; --i) std::swap(out[i - 1], out[below(engine, i)]);
}

const std::vector<int>& Timeline::order(std::int64_t pass) {
  for (const auto& c : cache_)
    if (c.pass == pass) return c.items;
  CachedOrder& c = cache_[cache_next_];
  cache_next_ = (cache_next_ + 1) % 3;
  c.pass = pass;
  const auto key = static_cast<std::uint64_t>(pass);
  shuffle_pass(key, c.items);
  // No item twice in a row across a pass boundary. Only the first two positions move, so the end
  // of the previous pass is its unadjusted one (with 3 or more items).
  if (c.items.size() >= 3) {
    shuffle_pass(key - 1, scratch_);
    if (c.items[0] == scratch_.back()) std::swap(c.items[0], c.items[1]);
  }
  return c.items;
}

int Timeline::item_at(std::int64_t slot) {
  const auto n = static_cast<std::int64_t>(playlist_.items.size());
  const std::int64_t pass = floor_div(slot, n);
  const std::int64_t pos = slot - pass * n;
  return shuffled() ? order(pass)[static_cast<std::size_t>(pos)] : static_cast<int>(pos);
}

// The first slot from `from` on (step +1) or back (step -1) whose item is playable.
std::int64_t Timeline::find_playable(std::int64_t from, int step) {
  const auto n = static_cast<std::int64_t>(playlist_.items.size());
  if (playable_count_ == 0) return none;
  // Two passes' worth: a window of one pass that straddles a boundary may miss an item.
  for (std::int64_t s = 0; s < 2 * n; ++s) {
    const std::int64_t g = from + step * s;
    if (!looping() && (g < 0 || g >= n)) return none;
    if (playable_[static_cast<std::size_t>(item_at(g))]) return g;
  }
  return none;
}

void Timeline::start(std::int64_t slot) {
  slot_ = slot;
  item_start_ = play_time_;
  active_ = true;
  finished_ = false;
  ++sequence_;
  cut_pending_ = true;
  fade_in_ = shown_any_;
}

void Timeline::run_sequential() {
  const auto n = static_cast<std::int64_t>(playlist_.items.size());
  if (n == 0 || playable_count_ == 0) {
    if (active_) cut_pending_ = true;
    active_ = false;
    return;
  }
  if (finished_) return;
  if (!active_ || !playable_[static_cast<std::size_t>(item_at(slot_))]) {
    const std::int64_t g = find_playable(active_ ? slot_ + 1 : slot_, +1);
    if (g == none) {
      if (active_) cut_pending_ = true;
      active_ = false;
      finished_ = true;
      return;
    }
    start(g);
  }
  for (;;) {
    const double d = duration(item_at(slot_));
    if (play_time_ - item_start_ < d) return;
    const std::int64_t g = find_playable(slot_ + 1, +1);
    if (g == none) {
      finished_ = true;
      return;
    }
    const bool new_pass = floor_div(g, n) != floor_div(slot_, n);
    item_start_ += d;
    slot_ = g;
    ++sequence_;
    cut_pending_ = true;
    fade_in_ = true;
    // A stalled caller: skip whole passes (each lasts playable_cycle() whatever its order), so the
    // loop runs at most about two passes' worth of items.
    if (new_pass && looping() && std::isfinite(playable_cycle())) {
      double k = std::floor((play_time_ - item_start_) / playable_cycle());
      while (k > 0 && item_start_ + k * playable_cycle() > play_time_) k -= 1;
      if (k >= 1 && k < 1e15) {
        const auto passes = static_cast<std::int64_t>(k);
        slot_ = find_playable((floor_div(g, n) + passes) * n, +1);
        item_start_ += k * playable_cycle();
        sequence_ += static_cast<std::uint64_t>(passes) * static_cast<std::uint64_t>(playable_count_);
      }
    }
  }
}

int Timeline::wall_slot_item(int slot) const {
  const int n = static_cast<int>(playlist_.items.size());
  for (int s = 0; s < n; ++s) {
    const int j = (slot + s) % n;
    if (playable_[static_cast<std::size_t>(j)]) return j;
  }
  return -1;
}

void Timeline::run_wallclock(double wall) {
  const int n = static_cast<int>(playlist_.items.size());
  if (n == 0) {
    wall_item_ = wall_next_ = -1;
    return;
  }
  const double cycle = slot_end_.back();
  double pos = std::fmod(wall, cycle);
  if (pos < 0) pos += cycle;
  if (!(pos < cycle)) pos = 0;  // NaN, or rounding up to the cycle
  const double count = std::floor((wall - pos) / cycle + 0.5);
  // pos < cycle, the last slot's end, so some slot ends after it.
  const int i = static_cast<int>(std::upper_bound(slot_end_.begin(), slot_end_.end(), pos) - slot_end_.begin());
  const double t = std::max(0.0, pos - (i ? slot_end_[static_cast<std::size_t>(i - 1)] : 0.0));
  const int shown = wall_slot_item(i);
  const bool changed = !wall_valid_ || count != wall_cycle_ || i != wall_slot_ || shown != wall_item_;
  if (changed && shown >= 0) {
    ++sequence_;
    cut_pending_ = true;
    fade_in_ = shown_any_;
  } else if (changed && wall_item_ >= 0) {
    cut_pending_ = true;
  } else if (!changed && std::abs(t - (wall_item_time_ + (last_now_ - wall_mono_))) > wall_jump_s) {
    cut_pending_ = true;  // the wall clock was stepped
  }
  wall_valid_ = true;
  wall_cycle_ = count;
  wall_mono_ = last_now_;
  wall_slot_ = i;
  wall_item_ = shown;
  wall_item_time_ = t;
  wall_next_ = wall_slot_item((i + 1) % n);
}

// The clock is already advanced; the wall time is extrapolated from the last at().
void Timeline::detach() {
  if (mode_ != Mode::wallclock) return;
  run_wallclock(last_wall_ + (last_now_ - last_wall_mono_));
  mode_ = Mode::local;
  finished_ = false;
  active_ = wall_item_ >= 0;
  slot_ = active_ ? wall_item_ : 0;
  item_start_ = play_time_ - (active_ ? wall_item_time_ : 0.0);
}

std::optional<int> Timeline::current_item() {
  const bool showing = mode_ == Mode::wallclock ? wall_valid_ && wall_item_ >= 0 : active_;
  if (!showing) return std::nullopt;
  return mode_ == Mode::wallclock ? wall_item_ : item_at(slot_);
}

double Timeline::current_item_time() const {
  if (mode_ == Mode::wallclock) return wall_item_time_;
  return play_time_ - item_start_;
}

float Timeline::fade(double t, double d, bool has_next) const {
  if (!(playlist_.fade_s > 0) || playable_count_ < 2) return 1.0f;
  const double half = playlist_.fade_s / 2;
  double f = 1;
  if (fade_in_ && t < half) f = std::min(f, t / half);
  if (has_next && d - t < half) f = std::min(f, (d - t) / half);
  return static_cast<float>(std::clamp(f, 0.0, 1.0));
}

Cue Timeline::at(double now, double wall_now) {
  advance_clock(now);
  last_wall_ = wall_now;
  last_wall_mono_ = last_now_;
  Cue f;
  double d = 0;
  if (mode_ == Mode::wallclock) {
    run_wallclock(wall_now);
    f.item = wall_item_;
    f.item_time = wall_item_time_;
    f.next_item = wall_next_;
    if (f.item >= 0) d = duration(wall_slot_);
  } else {
    run_sequential();
    f.finished = finished_;
    if (active_) {
      f.item = item_at(slot_);
      d = duration(f.item);
      f.item_time = finished_ ? d : std::clamp(play_time_ - item_start_, 0.0, d);
      if (!finished_) {
        const std::int64_t g = find_playable(slot_ + 1, +1);
        f.next_item = g == none ? -1 : item_at(g);
      }
    }
  }
  if (f.item >= 0) {
    f.camera = camera_at(playlist_.items[static_cast<std::size_t>(f.item)].camera, f.item_time);
    f.fade = fade(f.item_time, d, f.next_item >= 0);
    shown_any_ = true;
  }
  f.cut = cut_pending_;
  cut_pending_ = false;
  f.sequence = sequence_;
  return f;
}

void Timeline::next(double now) {
  advance_clock(now);
  detach();
  run_sequential();
  if (!active_ || finished_) return;
  const std::int64_t g = find_playable(slot_ + 1, +1);
  if (g == none) {
    finished_ = true;
    cut_pending_ = true;
    return;
  }
  start(g);
}

void Timeline::previous(double now) {
  advance_clock(now);
  detach();
  run_sequential();
  // From the end of a playlist that does not loop: the last item that can still be shown.
  if (finished_) {
    const std::int64_t g = find_playable(slot_, -1);
    if (g != none) start(g);
    return;
  }
  if (!active_) return;
  if (play_time_ - item_start_ < previous_window_s) {
    const std::int64_t g = find_playable(slot_ - 1, -1);
    start(g == none ? slot_ : g);
  } else {
    start(slot_);
  }
}

bool Timeline::show_item(int item, double now) {
  const auto n = static_cast<std::int64_t>(playlist_.items.size());
  if (item < 0 || item >= n || !playable_[static_cast<std::size_t>(item)]) return false;
  advance_clock(now);
  detach();
  run_sequential();
  const std::int64_t pass = floor_div(slot_, n);
  std::int64_t position = item;
  if (shuffled()) {
    const auto& o = order(pass);
    position = std::find(o.begin(), o.end(), item) - o.begin();
  }
  start(pass * n + position);
  return true;
}

void Timeline::restart(double now) {
  advance_clock(now);
  if (mode_ == Mode::wallclock) return;
  if (mode_ == Mode::local) {
    mode_ = Mode::wallclock;
    paused_ = false;
    wall_valid_ = false;  // the next at() starts whatever the schedule shows
    return;
  }
  run_sequential();
  if (active_) start(slot_);
}

void Timeline::pause(double now) {
  advance_clock(now);
  detach();
  paused_ = true;
}

void Timeline::resume(double now) {
  advance_clock(now);
  paused_ = false;
}

// Constant time: a scene that fails to load marks every item naming it, and a playlist of 100,000
// items would otherwise sum every duration once per item.
void Timeline::set_playable(int item, bool playable) {
  if (item < 0 || static_cast<std::size_t>(item) >= playable_.size()) return;
  char& flag = playable_[static_cast<std::size_t>(item)];
  if (flag == (playable ? 1 : 0)) return;
  flag = playable ? 1 : 0;
  const int sign = playable ? 1 : -1;
  playable_count_ += sign;
  const double d = duration(item);
  if (std::isfinite(d))
    finite_cycle_ += sign * d;
  else
    infinite_playable_ += sign;
  if (playable_count_ == 0) finite_cycle_ = 0;  // no rounding left behind when none plays
}

void Timeline::replace(Playlist playlist, double now) {
  advance_clock(now);
  if (mode_ == Mode::wallclock)
    run_wallclock(last_wall_ + (last_now_ - last_wall_mono_));
  else
    run_sequential();
  const std::optional<int> old_item = current_item();
  const double old_time = current_item_time();
  const std::string old_scene = old_item ? playlist_.items[static_cast<std::size_t>(*old_item)].scene : "";
  const auto old_n = static_cast<std::int64_t>(playlist_.items.size());
  const std::int64_t old_pass = mode_ != Mode::wallclock && old_n > 0 ? floor_div(slot_, old_n) : 0;

  reset_playlist(std::move(playlist));
  cut_pending_ = true;
  finished_ = false;
  active_ = false;
  slot_ = 0;
  const auto& items = playlist_.items;
  const auto n = static_cast<std::int64_t>(items.size());
  if (n == 0 || mode_ == Mode::wallclock) return;  // the schedule decides at the next at()

  std::optional<int> keep;
  if (old_item) {
    if (*old_item < n && items[static_cast<std::size_t>(*old_item)].scene == old_scene) keep = old_item;
    for (std::int64_t i = 0; !keep && i < n; ++i)
      if (items[static_cast<std::size_t>(i)].scene == old_scene) keep = static_cast<int>(i);
  }
  if (!keep) {
    run_sequential();  // starts the first item
    return;
  }
  const std::int64_t pass = looping() ? old_pass : 0;
  std::int64_t pos = *keep;
  if (shuffled()) {
    const auto& o = order(pass);
    pos = std::find(o.begin(), o.end(), *keep) - o.begin();
  }
  slot_ = pass * n + pos;
  item_start_ = play_time_ - old_time;
  active_ = true;
}

}  // namespace playback
