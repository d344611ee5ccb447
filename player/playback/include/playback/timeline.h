#pragma once
// The playback timeline: for a time t, which item to render, how far into it, from where, and how
// bright. Pure: no clocks are read here; the caller passes its monotonic time `now` (seconds, any
// origin, never going backwards: an earlier `now` is treated as equal to the latest) and, for the
// wallclock schedule, `wall_now` (seconds since the Unix epoch, UTC). Nothing here throws, and
// at() does not allocate once the shuffle order of the current pass is known.
//
// Sequential schedule: items in playlist order, or with shuffle = true in a new permutation every
// pass (deterministic from the seed and the pass number; with 3 or more items a pass never starts
// with the item the previous one ended with). loop = false: after the last item Cue.finished is
// set and the last item holds its final pose. A stalled caller lands on the right item in one
// call: whole passes are skipped arithmetically.
//
// Wallclock schedule: the position in the cycle (the sum of all durations, unplayable items
// included) is fmod(wall_now, cycle), so players sharing a playlist show the same item at the same
// moment without talking. shuffle and loop are ignored (the cycle always repeats). An unplayable
// item's slot shows the next playable item; the schedule does not shift.
// pause(), next() and previous() detach a wallclock timeline from the wall clock: it then plays
// sequentially, in playlist order and looping, on the local clock from where it was. restart()
// re-attaches it to the wall clock (and does nothing while it is attached); replace() with a
// wallclock playlist attaches too. Re-attaching is an item start (cut, sequence + 1).
//
// Fades: fade_s/2 out at the end of an item that is followed by another, fade_s/2 in at every
// item start except the first item this timeline shows (also after next/previous/restart, which
// cut without fading out). No fade when fade_s is 0 or at most one item is playable.
//
// Camera: turntable azimuth = azimuth_deg + 360 * item_time / period_s; still: fixed; orbit:
// Catmull-Rom through the keys per channel (non-uniform tangents, zero tangents at both ends so the
// camera eases into the hold after the last key; elevation and distance are kept within the keys'
// range). Cue azimuths are wrapped to [0, 360).

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "playback/playlist.h"

namespace playback {

struct Camera {                                                  // what scene::Framing takes
  double azimuth_deg{}, elevation_deg{}, distance{}, fov_deg{};  // camera_at() gives each, wherever an item shows
  int file_index = -1;  // >= 0: the scene's own camera of that index instead (motion = "file")
};

// What the playlist says should show at a time: the item, how far into it, the camera and the fade.
struct Cue {
  int item = -1;         // index into playlist().items; -1: nothing playable
  double item_time = 0;  // seconds since this item started (frozen while paused)
  Camera camera;
  float fade = 1;            // brightness multiplier in [0, 1]
  int next_item = -1;        // the item that follows (may equal `item`), to prepare in advance; -1 if none
  bool finished = false;     // loop = false and the last item is over
  bool cut = false;          // the item or camera jumped since the previous at() (true on the first call)
  std::uint64_t sequence{};  // + 1 at every item start (the first is 1); a kept item in replace() keeps it
};

// Where `path` puts the camera `t` seconds into an item (the Cue's camera).
Camera camera_at(const CameraPath& path, double t);

class Timeline {
 public:
  Timeline(Playlist playlist, double now, double wall_now);

  Cue at(double now, double wall_now);

  // Buttons. next(): the item that follows starts now (loop = false, last item: finished).
  // previous(): within the first 2 s of an item, the item before it (at the very first item of a
  // non-looping playlist: its start), else the start of the current item. restart(): the start of
  // the current item; on a detached wallclock timeline: re-attach (and un-pause), see above. Each
  // cuts and starts an item (sequence + 1), except restart() of an attached wallclock timeline,
  // which does nothing.
  void next(double now);
  void previous(double now);
  void restart(double now);
  // The playlist's item `item` (counted from 0, as the status file counts) starts now, in the pass
  // that is playing: a shuffled playlist goes on from that item's place in its pass; a finished one
  // plays again from there. Detaches a wallclock timeline, as next() does. False, and nothing
  // changes, when the playlist has no such item or its scene cannot be shown.
  bool show_item(int item, double now);

  // While paused the playlist clock stops: item_time and the camera hold. Buttons still work.
  void pause(double now);
  void resume(double now);
  bool paused() const { return paused_; }

  // Items whose scene failed to load are skipped; if none is playable, Cue.item = -1. Takes effect
  // at the next at(): a current item marked unplayable gives way to the next playable one.
  void set_playable(int item, bool playable);

  // Hot reload. Sequential: keeps playing the item with the same scene path (the same index if it
  // still has that scene, else the first with it) at the same item_time and sequence; else starts
  // the first item. Wallclock: the schedule decides (an item start). Every item is playable again.
  // Always a cut.
  void replace(Playlist playlist, double now);

  const Playlist& playlist() const { return playlist_; }

 private:
  enum class Mode { sequential, wallclock, local };  // local: a detached wallclock timeline
  static constexpr std::int64_t none = std::numeric_limits<std::int64_t>::min();

  void reset_playlist(Playlist playlist);
  void advance_clock(double now);
  bool looping() const;
  bool shuffled() const;
  double duration(int item) const;
  int item_at(std::int64_t slot);
  const std::vector<int>& order(std::int64_t pass);
  void shuffle_pass(std::uint64_t pass, std::vector<int>& out) const;
  std::int64_t find_playable(std::int64_t from, int step);
  void start(std::int64_t slot);
  void run_sequential();
  void run_wallclock(double wall);
  int wall_slot_item(int slot) const;
  void detach();
  float fade(double t, double duration, bool has_next) const;
  double current_item_time() const;
  std::optional<int> current_item();

  Playlist playlist_;
  std::vector<char> playable_;
  // Members initialised with {} are set before they are read: by the constructor, reset_playlist(), or
  // (the wallclock ones) by run_wallclock() before wall_valid_ lets anything read them.
  int playable_count_{};
  // The sum of playable durations (sequential fast-forward), from the two kept item by item.
  double playable_cycle() const;
  double finite_cycle_{};         // the playable items' finite durations, summed
  int infinite_playable_{};       // playable items of infinite duration (the cycle is then infinite)
  std::vector<double> slot_end_;  // wallclock: end of each item's slot in the cycle
  Mode mode_ = Mode::sequential;

  double last_now_{}, play_time_ = 0;
  double last_wall_{}, last_wall_mono_{};
  bool paused_ = false;

  // Sequential and local: the current slot (pass * items + position) and when it started.
  std::int64_t slot_ = 0;
  double item_start_ = 0;
  bool active_ = false, finished_ = false;

  // Wallclock: the slot shown at the last evaluation.
  bool wall_valid_ = false;
  double wall_cycle_{}, wall_mono_{};
  int wall_slot_{}, wall_item_{}, wall_next_{};
  double wall_item_time_ = 0;

  std::uint64_t sequence_ = 0;
  bool cut_pending_ = true, fade_in_ = false, shown_any_ = false;

  struct CachedOrder {
    std::int64_t pass = none;
    std::vector<int> items;
  };
  CachedOrder cache_[3];
  int cache_next_ = 0;
  std::vector<int> scratch_;
};

}  // namespace playback
