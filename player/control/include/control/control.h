#pragma once
// The player's local control socket: an AF_UNIX SOCK_SEQPACKET socket (one message per command,
// one reply, then the connection closes), for people on the box (`player ctl`), scripts and the
// fleet agent. The player reads it in its poll loop and never waits on a client.
//
// A command is one line of ASCII: a verb and its arguments separated by single spaces, at most
// kMaxMessage bytes ("next", "item 2"). A reply is one line: "ok" or "ok: what was done", or
// "error: why" (nothing was changed).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace control {

inline constexpr std::size_t kMaxMessage = 256;
inline constexpr std::string_view kDefaultPath = "/run/ssao-player/control";
// Members of this group may command a player besides root and the player's own user.
inline constexpr std::string_view kControlGroup = "ssao-player-control";

enum class Verb : std::uint8_t { next, previous, pause, resume, check, reload, restart, item, screenshot, display };

struct Command {
  Verb verb = Verb::next;
  int item = -1;           // `item N`: the playlist's item N, counted from 0 as in the status file
  bool display_on = true;  // `display on|off`
};

std::string_view to_string(Verb verb);
// "next, previous, ..., item N, screenshot, display on|off": for errors and --help.
std::string verbs_text();
// One message as a command. False and why (the message shown as it came, escaped).
bool parse_command(std::string_view message, Command& out, std::string& error);
// The command as its message: parse_command(format_command(c)) gives c back.
std::string format_command(const Command& command);
// Whether a reply says the command was done.
bool reply_ok(std::string_view reply);

// Sends one message to the socket at `path` and reads the reply, within `timeout_ms` in all.
// False and why (no socket, no player listening, no permission, no reply in time).
bool send_command(const std::string& path, std::string_view message, int timeout_ms, std::string& reply, std::string& error);

}  // namespace control
