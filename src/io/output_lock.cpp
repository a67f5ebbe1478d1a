#include "io/output_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "util/error.h"

namespace clppm {

std::string OutputLock::lock_path(const std::string& path) {
    const std::filesystem::path p(path);
    return (p.parent_path() / ("." + p.filename().string() + ".clppm-lock")).string();
}

OutputLock::OutputLock(const std::vector<std::string>& paths) {
    for (const std::string& path : paths) {
        const std::string lock = lock_path(path);
        bool already = false;
        for (const Held& h : held_) already = already || h.path == lock;
        if (already) continue;
        const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0) continue; // an unwritable directory: check_writable reports it
        if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
            char owner[32] = {0};
            const ssize_t n = ::pread(fd, owner, sizeof owner - 1, 0);
            ::close(fd);
            std::string pid = n > 0 ? std::string(owner, size_t(n)) : std::string();
            while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
            throw Error(path + " is being written by another clppm render" + (pid.empty() ? "" : " (pid " + pid + ")") +
                        "; give this one other outputs, or wait for it to finish");
        }
        const std::string me = std::to_string(::getpid()) + "\n";
        if (::ftruncate(fd, 0) == 0) {
            const ssize_t w = ::pwrite(fd, me.data(), me.size(), 0);
            (void)w; // the pid is only for the message
        }
        held_.push_back({lock, fd});
    }
}

OutputLock::~OutputLock() {
    for (const Held& h : held_) {
        ::unlink(h.path.c_str());
        ::close(h.fd);
    }
}

} // namespace clppm
