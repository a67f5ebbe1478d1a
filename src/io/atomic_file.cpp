#include "io/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/error.h"

namespace clppm {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
    throw Error("cannot write " + path + ": " + reason);
}

std::string base_name(const std::string& path) {
    size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

// ".<name>.tmp.<pid>.<n>" in the target's directory: rename() is only atomic within one file
// system, and n tells apart the writes of several threads (several renders in one process).
std::string temp_path_for(const std::string& path) {
    static std::atomic<unsigned long> writes{0};
    size_t slash = path.find_last_of('/');
    std::string dir_prefix = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    return dir_prefix + "." + base_name(path) + ".tmp." + std::to_string(::getpid()) + "." +
           std::to_string(writes.fetch_add(1));
}

bool is_directory(const std::string& path) {
    struct stat st;
    return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

// Why the temp file could not be created, in the user's terms (the directory, not the temp name).
std::string create_failure_reason(const std::string& path, int err) {
    std::string dir = parent_directory(path);
    struct stat st;
    if (err == ENOENT || (err == ENOTDIR && ::stat(dir.c_str(), &st) != 0))
        return "directory " + dir + " does not exist";
    if (err == ENOTDIR) return dir + " is not a directory";
    return std::string(std::strerror(err)) + " (directory " + dir + ")";
}

bool write_all(int fd, const char* data, size_t size) {
    while (size > 0) {
        ssize_t n = ::write(fd, data, size);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return false;
        if (n == 0) { // no progress on a regular file means no room
            errno = ENOSPC;
            return false;
        }
        data += n;
        size -= static_cast<size_t>(n);
    }
    return true;
}

// The rename is durable only once the directory entry is on disk; best effort, since some file
// systems refuse fsync on directories and the data itself is already safe.
void sync_directory(const std::string& dir) {
    int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    (void)::fsync(fd);
    ::close(fd);
}

// The temp file beside the target; removed unless commit() renamed it into place.
class TempFile {
public:
    explicit TempFile(const std::string& target) : target_(target), temp_(temp_path_for(target)) {
        fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd_ < 0) fail(target_, create_failure_reason(target_, errno));
    }
    ~TempFile() {
        if (fd_ >= 0) ::close(fd_);
        if (!committed_) ::unlink(temp_.c_str());
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    void write(const std::string& contents) {
        if (!write_all(fd_, contents.data(), contents.size())) fail(target_, std::strerror(errno));
    }
    void commit() {
        if (::fsync(fd_) != 0) fail(target_, std::strerror(errno));
        int rc = ::close(fd_); // NFS and quota errors can surface only at close
        fd_ = -1;
        if (rc != 0) fail(target_, std::strerror(errno));
        if (::rename(temp_.c_str(), target_.c_str()) != 0) fail(target_, std::strerror(errno));
        committed_ = true;
        sync_directory(parent_directory(target_));
    }

private:
    std::string target_;
    std::string temp_;
    int fd_ = -1;
    bool committed_ = false;
};

void check_target_name(const std::string& path) {
    if (path.empty()) throw Error("cannot write a file with an empty name");
    if (path.back() == '/' || is_directory(path)) fail(path, "it is a directory");
}

} // namespace

std::string parent_directory(const std::string& path) {
    size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return ".";
    if (slash == 0) return "/";
    return path.substr(0, slash);
}

void write_file_atomic(const std::string& path, const std::string& contents) {
    check_target_name(path);
    TempFile file(path);
    file.write(contents);
    file.commit();
}

void check_writable(const std::string& path) {
    check_target_name(path);
    TempFile probe(path); // removed again when it goes out of scope
}

} // namespace clppm
