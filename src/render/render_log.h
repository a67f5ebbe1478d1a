// What a render says as it is set up and runs, on stderr as "clppm: ..." lines: notes (what clppm
// is doing; quiet hides them) and warnings (what the user must know about the result; always
// said). With several processes only rank 0 speaks: the others would say the same. Warnings are
// kept too, for front ends that hand them on (the Python module's Renderer.warnings).
#pragma once
#include <string>
#include <vector>

namespace clppm {

class RenderLog {
public:
    explicit RenderLog(bool quiet);
    // A log that keeps its warnings and says nothing at all: --device auto's trial renders.
    static RenderLog silent();
    void note(const std::string& message) const;
    void warn(const std::string& message);
    // A defect found in the result ("2 pixels are NaN"), said as an error line; the render has
    // still written what it has.
    void error(const std::string& message);
    const std::vector<std::string>& warnings() const { return warnings_; }
    bool quiet() const { return quiet_; }

private:
    bool quiet_;
    bool speaks_; // rank 0, or the only process, unless silent
    std::vector<std::string> warnings_;
};

} // namespace clppm
