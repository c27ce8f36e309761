// A pointing hand drawn as a binary mask: a palm disc, an index finger and a short thumb,
// shared by the contour, measurement and template-trial tests.
#pragma once

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numbers>
#include <vector>

namespace gc_test {

inline cv::Mat1b drawn_hand(cv::Size size, cv::Point2d palm, double finger_deg, double s)
{
    cv::Mat1b m(size, uchar(0));
    cv::circle(m, palm, cvRound(22 * s), 255, cv::FILLED, cv::LINE_8);
    const double a = finger_deg * std::numbers::pi / 180.0;
    const cv::Point2d dir(std::cos(a), -std::sin(a));
    const cv::Point2d side(-dir.y, dir.x);
    const cv::Point2d base = palm + dir * (15 * s), tip = palm + dir * (62 * s);
    std::vector<cv::Point> finger{base + side * (5 * s), tip + side * (5 * s), tip - side * (5 * s),
                                  base - side * (5 * s)};
    cv::fillConvexPoly(m, finger, 255);
    cv::circle(m, tip, cvRound(5 * s), 255, cv::FILLED);
    cv::circle(m, palm + side * (26 * s) + dir * (6 * s), cvRound(7 * s), 255, cv::FILLED);
    return m;
}

}  // namespace gc_test
