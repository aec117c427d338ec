// SPDX-License-Identifier: MIT
// directory_lock.h — one writer per output directory: a job that writes a directory holds an
// exclusive lock on `<dir>/.pemref.lock` for its lifetime, so a second job started on the same
// directory refuses at once instead of corrupting the first one's files.
//
//   const DirectoryLock lock("out/bake");   // throws base::InputError if another job holds it
//
// Conventions: flock(2), advisory; the kernel releases it when the process ends, however it ends
// (a killed bake leaves no stale lock); the file itself stays (empty but for the holder's pid).
// Not here: locks across machines (flock on NFS is not relied upon).
#pragma once

#include <string>

namespace pem::base {

class DirectoryLock {
  public:
    explicit DirectoryLock(const std::string& dir);
    ~DirectoryLock();
    DirectoryLock(const DirectoryLock&) = delete;
    DirectoryLock& operator=(const DirectoryLock&) = delete;

  private:
    int fd_ = -1;
};

}  // namespace pem::base
