// SPDX-License-Identifier: MIT
// directory_lock.cpp — flock on <dir>/.pemref.lock (directory_lock.h).
#include "base/directory_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "base/input_error.h"

namespace pem::base {

DirectoryLock::DirectoryLock(const std::string& dir) {
    const std::string path = dir + "/.pemref.lock";
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
        throw InputError(path, std::string("cannot open the lock: ") + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        char holder[32] = {};
        const ssize_t n = ::pread(fd_, holder, sizeof holder - 1, 0);
        ::close(fd_);
        fd_ = -1;
        throw InputError(dir, "another pemref job is writing this directory" +
                                  (n > 0 ? std::string(" (pid ") + holder + ")" : std::string()));
    }
    const std::string pid = std::to_string(::getpid());
    if (::ftruncate(fd_, 0) == 0) {
        const ssize_t w = ::pwrite(fd_, pid.data(), pid.size(), 0);
        (void)w;  // the pid is only for the message
    }
}

DirectoryLock::~DirectoryLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the flock
}

}  // namespace pem::base
