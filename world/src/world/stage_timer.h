// Timing a step's stages: each adds the milliseconds of its scope to a StepStats field.
#pragma once

#include <chrono>

namespace cyclone::detail {

class StageTimer {
public:
    explicit StageTimer(double &total) : total_(total) {}
    StageTimer(const StageTimer &) = delete;
    StageTimer &operator=(const StageTimer &) = delete;
    ~StageTimer() { total_ += elapsed(); }

    /// Milliseconds since the timer started.
    double elapsed() const {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    double &total_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace cyclone::detail
