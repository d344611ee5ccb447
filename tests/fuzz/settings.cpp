// The render settings codec (render::apply_settings): `--set`-style "key=value,..." text from the
// command line, playlists and aobench. Besides never crashing, the codec must read back what it
// writes: describe() of an accepted list, applied to fresh settings, gives the same description.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "render/settings.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const render::FrameSettings base;
  render::FrameSettings settings;
  std::string error;
  if (!render::apply_settings(settings, text, error)) return 0;
  for (const render::SettingKey& key : render::setting_keys()) (void)render::setting_value(settings, key.key);
  const std::string described = render::describe(settings, base);
  render::FrameSettings again;
  if (!render::apply_settings(again, described, error)) __builtin_trap();  // it wrote what it cannot read
  if (render::describe(again, base) != described) __builtin_trap();        // and reads it as something else
  return 0;
}
