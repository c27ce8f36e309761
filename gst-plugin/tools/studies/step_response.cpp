// Step response of the fixate law (FixateController) against the simulated head's mechanics
// (HeadModel), in simulated time: no sockets, no threads, deterministic. The timing is the
// closed-loop test's: 30 frames/s, each frame's command submitted 10 ms after its capture,
// the head obeying 20 ms after that. A hand appears off centre at t = 0 and holds still.
//
//   step_response [--csv FILE]
//
// Prints overshoot, rise and settling times per step and axis, and exits 1 when a step
// overshoots by more than 2 deg, does not settle or keeps moving at the end. With --csv it
// also writes the trajectories for docs/plots/make_step_plot.py.
#include "headctl/steering/fixate_controller.hpp"
#include "headctl/sim/head_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace gc;
using namespace gc::headctl;

constexpr double kFrame = 1.0 / 30.0;
constexpr int kSubsteps = 10;       // trajectory samples per frame (3.3 ms)
constexpr int kCommandSubstep = 3;  // the command leaves 10 ms after the capture
constexpr double kHeadLatency = 0.02;
constexpr double kDuration = 3.0;
// HeadLink's smoothing of the hand's angular velocity per frame (headctl/steering/head_link.cpp).
constexpr double kRateSmoothing = 0.3;

struct Sample {
    double t, pan, tilt, cmd_pan, cmd_tilt;
};

struct Step {
    const char* name;
    double pan, tilt;  // where the hand appears, degrees from the optical axis
};

struct AxisFigures {
    double overshoot = 0.0;  // beyond the target, degrees (0 when it never passes it)
    double rise_s = NAN;     // from 10 % to 90 % of the final value (the dead band stops
                             // the axis short of the target, so not of the step)
    double settle_s = NAN;   // from then on within the dead band (1 deg) of the target
    double rest_s = NAN;     // last movement of the axis
    double final_error = 0.0;
};

std::vector<Sample> run(const Step& step)
{
    FixateConfig fc;
    fc.limits = default_simulated_limits();  // what the head reports to the link
    FixateController controller(fc);
    HeadModelConfig mc;
    mc.latency_s = kHeadLatency;
    HeadModel head(mc);

    std::vector<Sample> out;
    double cmd_pan = 0.0, cmd_tilt = 0.0;
    bool have_direction = false;
    double last_pan_dir = 0.0, last_tilt_dir = 0.0, rate_pan = 0.0, rate_tilt = 0.0;
    const int frames = static_cast<int>(std::lround(kDuration / kFrame));
    for (int k = 0; k < frames; ++k) {
        HeadPose capture;
        for (int j = 0; j < kSubsteps; ++j) {
            const double t = (k + double(j) / kSubsteps) * kFrame;
            const HeadPose pose = head.state(t).pose;
            if (j == 0) capture = pose;
            if (j == kCommandSubstep) {
                // The hand is fixed in the world; the frame shows it relative to the pose at
                // capture (a pure rotation: the offset is the angle difference).
                FixateObservation seen;
                seen.valid = true;
                seen.offset_pan_deg = step.pan - capture.pan_deg;
                seen.offset_tilt_deg = step.tilt - capture.tilt_deg;
                // The link's feed-forward input: the rate of the hand's line of sight in the
                // base frame, which for a still hand stays 0 however the head moves.
                const double pan_dir = capture.pan_deg + seen.offset_pan_deg;
                const double tilt_dir = capture.tilt_deg + seen.offset_tilt_deg;
                if (have_direction) {
                    rate_pan += kRateSmoothing * ((pan_dir - last_pan_dir) / kFrame - rate_pan);
                    rate_tilt += kRateSmoothing * ((tilt_dir - last_tilt_dir) / kFrame - rate_tilt);
                }
                have_direction = true;
                last_pan_dir = pan_dir;
                last_tilt_dir = tilt_dir;
                seen.rate_pan_dps = rate_pan;
                seen.rate_tilt_dps = rate_tilt;
                if (const auto command = controller.update(seen, pose, kFrame)) {
                    if (command->kind != CommandKind::Velocity) throw std::logic_error("unexpected command");
                    head.move_velocity(command->values, t);
                    cmd_pan = command->values.get(Axis::Pan);
                    cmd_tilt = command->values.get(Axis::Tilt);
                }
            }
            out.push_back({t, pose.pan_deg, pose.tilt_deg, cmd_pan, cmd_tilt});
        }
    }
    return out;
}

AxisFigures measure(const std::vector<Sample>& s, double target, double Sample::*axis, double dead_band)
{
    AxisFigures f;
    const double dir = target >= 0.0 ? 1.0 : -1.0;
    const double reached = s.back().*axis * dir;
    double t10 = NAN, t90 = NAN;
    for (const Sample& x : s) {
        const double progress = (x.*axis) * dir;  // towards the target, degrees
        f.overshoot = std::max(f.overshoot, progress - std::abs(target));
        if (std::isnan(t10) && progress >= 0.1 * reached) t10 = x.t;
        if (std::isnan(t90) && progress >= 0.9 * reached) t90 = x.t;
    }
    f.rise_s = t90 - t10;
    for (std::size_t i = s.size(); i-- > 0;) {
        if (std::isnan(f.settle_s) && std::abs(s[i].*axis - target) > dead_band)
            f.settle_s = i + 1 < s.size() ? s[i + 1].t : NAN;
        if (std::isnan(f.rest_s) && i > 0 && s[i].*axis != s[i - 1].*axis) f.rest_s = s[i].t;
    }
    if (std::isnan(f.settle_s) && std::abs(s.front().*axis - target) <= dead_band) f.settle_s = 0.0;
    f.final_error = s.back().*axis - target;
    return f;
}

}  // namespace

int main(int argc, char** argv)
{
    const char* csv_path = nullptr;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--csv") == 0 && i + 1 < argc)
            csv_path = argv[++i];
        else {
            std::fprintf(stderr, "usage: %s [--csv FILE]\n", argv[0]);
            return 2;
        }
    }
    FILE* csv = nullptr;
    if (csv_path) {
        csv = std::fopen(csv_path, "w");
        if (!csv) {
            std::perror(csv_path);
            return 2;
        }
        std::fprintf(csv, "step,t_s,target_pan_deg,target_tilt_deg,pan_deg,tilt_deg,cmd_pan_dps,cmd_tilt_dps\n");
    }

    const FixateConfig defaults;
    const Step steps[] = {{"10 right and 5 up", 10.0, 5.0}, {"20 right and 10 down", 20.0, -10.0}};
    bool ok = true;
    for (const Step& step : steps) {
        const std::vector<Sample> s = run(step);
        if (csv)
            for (const Sample& x : s)
                std::fprintf(csv, "%s,%.4f,%.1f,%.1f,%.4f,%.4f,%.3f,%.3f\n", step.name, x.t, step.pan, step.tilt, x.pan,
                             x.tilt, x.cmd_pan, x.cmd_tilt);
        const struct {
            const char* name;
            double target;
            double Sample::*axis;
        } axes[] = {{"pan", step.pan, &Sample::pan}, {"tilt", step.tilt, &Sample::tilt}};
        for (const auto& a : axes) {
            const AxisFigures f = measure(s, a.target, a.axis, defaults.dead_band_deg);
            std::printf("step %-20s %-4s %+5.1f deg: overshoot %.3f deg, rise (10-90 %%) %.3f s, within %.0f deg "
                        "from %.3f s, at rest from %.3f s, final error %+.3f deg\n",
                        step.name, a.name, a.target, f.overshoot, f.rise_s, defaults.dead_band_deg, f.settle_s,
                        f.rest_s, f.final_error);
            // At most 2 deg of overshoot; settled inside the dead band, and still for the
            // last second (no oscillation at rest).
            if (!(f.overshoot <= 2.0) || !(f.settle_s <= kDuration - 1.0) || !(f.rest_s <= kDuration - 1.0) ||
                !(std::abs(f.final_error) <= defaults.dead_band_deg)) {
                std::printf("  FAILED\n");
                ok = false;
            }
        }
    }
    if (csv) std::fclose(csv);
    return ok ? 0 : 1;
}
