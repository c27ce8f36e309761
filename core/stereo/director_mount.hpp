// A second PTZ camera, the director, that frames what a held pointing picks while the stereo
// head keeps watching the hand. Where it stands in the head frame, what its lens sees at its
// widest zoom, and the pan, tilt and zoom that frame a region of the room.
#pragma once

#include "common/types.hpp"
#include "stereo/head_geometry.hpp"

#include <opencv2/core.hpp>

#include <optional>

namespace gc {

// Pan and tilt turn the camera about its base's origin (pan about the base's y axis, then
// tilt about the turned x axis), like the stereo head's neck with both centres at the origin.
struct DirectorMount {
    cv::Size image_size{1920, 1080};
    cv::Matx33d K{1662.8, 0.0, 959.5, 0.0, 1662.8, 539.5, 0.0, 0.0, 1.0};  // at zoom 1 (60 deg across)
    RigidTransform head_to_base;  // X_base = R X_head + T, millimetres; the base is the camera at pan = tilt = 0
};

// Where a region shows in the director's picture: its centre as fractions of the picture's
// width and height (0.5, 0.5 in the middle) and its width over the picture's.
struct DirectorPlacement {
    cv::Point2d centre;
    double fill = 0.0;
};

// The director camera's frame at `pose` (pan, tilt, zoom) from the head frame.
RigidTransform head_to_director_camera(const DirectorMount& mount, const HeadPose& pose);

// A head-frame region `size_mm` wide around `centre_mm` in the director's picture at `pose`;
// nullopt when it lies behind the camera. Lens distortion is left out.
std::optional<DirectorPlacement> place_in_director(const DirectorMount& mount, const HeadPose& pose,
                                                   const cv::Vec3d& centre_mm, double size_mm);

// The pan, tilt (degrees) and zoom that put `centre_mm` in the middle of the director's
// picture with a region `size_mm` wide across its width, the zoom kept in [zoom_min,
// zoom_max]. Vergence is left at 0.
HeadPose director_aim(const DirectorMount& mount, const cv::Vec3d& centre_mm, double size_mm, double zoom_min,
                      double zoom_max);

}  // namespace gc
