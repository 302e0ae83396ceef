#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "client/farm/server_list.h"

namespace glint {

// Where the farm's servers come from, and how the set changes while glint
// runs: the --server values, whose names are resolved again every few
// seconds (a Kubernetes headless Service that scales its pods changes the
// farm), and a --server-file, read again whenever its text changes. Asked
// between frames (refresh()); the pool then adds and drops servers.
class ServerSource {
 public:
  using Clock = std::chrono::steady_clock;
  // Entries -> addresses (resolveEntries; a test passes its own).
  using Resolve = std::function<std::vector<ServerAddress>(const std::vector<ServerEntry>&)>;
  // A name is resolved again this often.
  static constexpr std::chrono::seconds kResolveEvery{5};

  // A fixed set, as already resolved: refresh() never changes it.
  ServerSource(std::vector<ServerAddress> addresses);  // NOLINT(google-explicit-constructor): tests pass a list
  // The values and the file (either may be empty, not both), read and
  // resolved now. Throws InputError naming what cannot be used, or saying
  // that no server is listed.
  ServerSource(std::vector<std::string> values, std::string file, Clock::time_point now,
               Resolve resolve = [](const std::vector<ServerEntry>& e) { return resolveEntries(e); });

  const std::vector<ServerAddress>& addresses() const { return addresses_; }
  // Reads the file again, and resolves again when kResolveEvery has passed
  // since the last time; true when the addresses changed. A file that
  // cannot be read or used, or a name that no longer resolves, keeps the
  // addresses as they were and says why in warning() (once per cause).
  bool refresh(Clock::time_point now);
  // What the last refresh could not use; "" when it used everything.
  const std::string& warning() const { return warning_; }

 private:
  // The values' and the file's entries; throws InputError.
  std::vector<ServerEntry> entries(const std::string& fileText) const;

  std::vector<std::string> values_;
  std::string file_;
  Resolve resolve_;
  std::string fileText_;  // as last read and tried
  Clock::time_point resolvedAt_{};
  std::vector<ServerAddress> addresses_;
  std::string warning_;
};

}  // namespace glint
