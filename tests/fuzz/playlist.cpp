// Playlists (playback::parse_playlist) with the options the player passes: a content root and the
// render settings codec as the validator of each item's `ao` table. Nothing may throw out of it.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_dir.h"
#include "playback/playlist.h"
#include "render/settings.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string source = (fuzz::scratch_dir() / "playlist.toml").string();
  static const playback::ParseOptions options = [] {
    playback::ParseOptions o;
    o.content_root = fuzz::scratch_dir().string();
    o.validate_setting = render::validate_setting;
    return o;
  }();
  playback::Playlist playlist;
  std::string error;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (parse_playlist(text, source, options, playlist, error)) {
    // What the player does next: apply each item's settings to a frame.
    for (const playback::Item& item : playlist.items) {
      render::FrameSettings settings;
      for (const playback::Setting& s : item.settings) {
        if (!render::apply_setting(settings, s.key, s.value, error)) __builtin_trap();  // validated, yet refused
      }
    }
  }
  return 0;
}
