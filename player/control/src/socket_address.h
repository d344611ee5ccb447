#pragma once
// The AF_UNIX address of a socket path, for both ends.
#include <sys/socket.h>
#include <sys/un.h>

#include <cstring>
#include <string>

namespace control {

// False and why when the path is empty or too long for sun_path (107 bytes on Linux).
inline bool socket_address(const std::string& path, sockaddr_un& address, std::string& error) {
  address = {};
  address.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof address.sun_path) {
    error = "the control socket's path '" + path + "' is empty or longer than " + std::to_string(sizeof address.sun_path - 1) +
            " bytes";
    return false;
  }
  std::memcpy(address.sun_path, path.data(), path.size());
  return true;
}

}  // namespace control
