// Exclusive use of a render's outputs: two renders given the same output paths would overwrite
// each other's files, leaving an EXR, stats and checkpoint from different runs. Each output path
// gets an advisory lock (flock on a hidden lock file beside it, ".NAME.clppm-lock", holding the
// owner's pid); a second render that finds one taken is refused before it renders. The kernel
// releases the locks when the process ends, however it ends; the lock files are removed on a
// normal exit.
#pragma once
#include <string>
#include <vector>

namespace clppm {

class OutputLock {
public:
    // Locks every path; throws Error naming the first that another process holds.
    explicit OutputLock(const std::vector<std::string>& paths);
    ~OutputLock();
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

    // The lock file of an output path.
    static std::string lock_path(const std::string& path);

private:
    struct Held {
        std::string path;
        int fd;
    };
    std::vector<Held> held_;
};

} // namespace clppm
