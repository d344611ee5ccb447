#pragma once
// `player ctl VERB [ARGS]`: one command to a running player through its control socket.
#include <iosfwd>
#include <string>
#include <vector>

namespace app {

struct CtlOptions {
  std::vector<std::string> words;  // the verb and its arguments, as typed
  std::string control;             // the socket's path
  double timeout_s = 5.0;
};

// 0: the player did it; 1: it refused (its reply says why); 2: no player could be asked.
int run_ctl(const CtlOptions& options, std::ostream& out, std::ostream& err);

}  // namespace app
