#include "tracker/stereo_tracker.hpp"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace gc {

namespace {

// splitmix64: a well-mixed, reproducible seed for the right eye from the left eye's.
std::uint64_t derive_seed(std::uint64_t seed)
{
    std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

TrackerParams right_params(TrackerParams p)
{
    p.seed = derive_seed(p.seed);
    return p;
}

}  // namespace

// The right eye runs on one persistent worker: the caller posts a frame, tracks the left
// eye itself, then waits for the worker. Nothing is allocated per frame.
struct StereoHandTracker::Impl {
    HandTracker left;
    HandTracker right;

    std::mutex mutex;
    std::condition_variable wake;
    std::condition_variable done;
    const cv::Mat* job_frame = nullptr;
    ImageMotion job_motion;
    bool job_pending = false;
    bool job_done = false;
    bool stopping = false;
    std::exception_ptr job_error;
    std::thread worker;

    explicit Impl(const TrackerParams& params) : left(params), right(right_params(params)), worker([this] { run(); }) {}

    ~Impl()
    {
        {
            std::lock_guard lock(mutex);
            stopping = true;
        }
        wake.notify_one();
        worker.join();
    }

    void run()
    {
        std::unique_lock lock(mutex);
        for (;;) {
            wake.wait(lock, [this] { return job_pending || stopping; });
            if (stopping) return;
            job_pending = false;
            const cv::Mat* frame = job_frame;
            const ImageMotion motion = job_motion;
            lock.unlock();
            std::exception_ptr error;
            try {
                right.process(*frame, motion);
            } catch (...) {
                error = std::current_exception();
            }
            lock.lock();
            job_error = error;
            job_done = true;
            done.notify_one();
        }
    }

    StereoEstimate process(const cv::Mat& l, const cv::Mat& r, const ImageMotion& lm, const ImageMotion& rm)
    {
        {
            std::lock_guard lock(mutex);
            job_frame = &r;
            job_motion = rm;
            job_pending = true;
            job_done = false;
            job_error = nullptr;
        }
        wake.notify_one();
        std::exception_ptr left_error;
        try {
            left.process(l, lm);
        } catch (...) {
            left_error = std::current_exception();
        }
        std::exception_ptr right_error;
        {
            // Always wait: the worker reads `r`, which the caller owns.
            std::unique_lock lock(mutex);
            done.wait(lock, [this] { return job_done; });
            right_error = job_error;
        }
        if (left_error) std::rethrow_exception(left_error);
        if (right_error) std::rethrow_exception(right_error);
        return {left.estimate(), right.estimate()};
    }
};

StereoHandTracker::StereoHandTracker(const TrackerParams& params) : impl_(std::make_unique<Impl>(params)) {}

StereoHandTracker::~StereoHandTracker() = default;

StereoEstimate StereoHandTracker::process(const cv::Mat& left_bgr, const cv::Mat& right_bgr,
                                          const ImageMotion& left_motion, const ImageMotion& right_motion)
{
    return impl_->process(left_bgr, right_bgr, left_motion, right_motion);
}

void StereoHandTracker::reset()
{
    impl_->left.reset();
    impl_->right.reset();
}

const HandTracker& StereoHandTracker::eye(Eye e) const { return e == Eye::Left ? impl_->left : impl_->right; }

}  // namespace gc
