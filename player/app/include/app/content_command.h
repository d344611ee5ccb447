#pragma once
// `player content install|rollback|list`: versioned content bundles (content/content.h).
#include <iosfwd>
#include <string>

namespace app {

struct ContentOptions {
  std::string action;  // install, rollback or list
  std::string source;  // install: the folder or .tar
  std::string root;
  int keep = 3;
  std::string max_size = "4G";
};

// 0: done; 1: refused (the bundle, or nothing to roll back to); 2: bad usage.
int run_content(const ContentOptions& options, std::ostream& out, std::ostream& err);

}  // namespace app
