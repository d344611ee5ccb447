#include "app/content_command.h"

#include "base/read_file.h"
#include "content/content.h"

#include <charconv>
#include <cstdio>
#include <ostream>

namespace app {
namespace {

// "500M", "4G", "1048576": bytes with an optional K, M or G (powers of 1024).
bool parse_bytes(const std::string& text, std::uint64_t& bytes) {
  std::uint64_t number = 0;
  const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), number);
  if (status != std::errc() || end == text.data()) return false;
  const std::string_view unit(end, static_cast<std::size_t>(text.data() + text.size() - end));
  const std::uint64_t scale = unit.empty()  ? 1
                              : unit == "K" ? base::kKiB
                              : unit == "M" ? base::kMiB
                              : unit == "G" ? base::kGiB
                                            : 0;
  if (scale == 0 || number == 0 || number > (std::uint64_t(1) << 50) / scale) return false;
  bytes = number * scale;
  return true;
}

}  // namespace

int run_content(const ContentOptions& options, std::ostream& out, std::ostream& err) {
  std::string error;
  if (options.action == "install" || options.action == "take") {
    content::InstallOptions install;
    install.root = options.root;
    install.source = options.source;
    install.keep = options.keep;
    if (!parse_bytes(options.max_size, install.max_bytes)) {
      err << "error: --max-size: expected bytes with an optional K, M or G (e.g. 500M), got '" << options.max_size << "'\n";
      return 2;
    }
    std::vector<std::string> bundles{options.source};
    if (options.action == "take" && !content::waiting_bundles(options.source, bundles, error)) {
      err << "error: " << error << "\n";
      return 1;
    }
    int refused = 0;
    for (const std::string& bundle : bundles) {
      install.source = bundle;
      std::string id;
      if (!content::install(install, out, id, error)) {
        err << "error: " << error << "\n";
        ++refused;
      }
      // Taken whatever the outcome: a refused bundle is reported (the record), not tried forever.
      if (options.action == "take" && std::remove(bundle.c_str()) != 0) {
        err << "error: " << bundle << ": cannot remove it from the inbox\n";
        ++refused;
      }
    }
    if (options.action == "take" && bundles.empty()) out << "no bundle waits in " << options.source << "\n";
    return refused == 0 ? 0 : 1;
  }
  if (options.action == "rollback") {
    if (!content::rollback(options.root, out, error)) {
      err << "error: " << error << "\n";
      return 1;
    }
    return 0;
  }
  std::vector<content::Version> versions;
  if (!content::list(options.root, versions, error)) {
    err << "error: " << error << "\n";
    return 1;
  }
  for (const content::Version& v : versions)
    out << (v.current ? "* " : "  ") << v.id << "  " << v.files << " files, " << base::byte_size_text(v.bytes) << "\n";
  if (versions.empty()) out << "no version installed in " << options.root << "\n";
  return 0;
}

}  // namespace app
