// duration = "auto": whether every piece has come to rest over a hold of recorded frames.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/model.h"
#include "core/trajectory.h"

namespace shatter {

class BulletWorld;

class RestCheck {
public:
    // `radius`: each piece's (piece_radius); `fps`: the trajectory's frames per second.
    RestCheck(const Model& model, const BulletWorld& world, const std::vector<double>& radius, double fps);

    // Every dynamic piece of `t` stayed within reach of its pose at frame `from` up to frame `to`,
    // below the rest speed `rest` (and, once `landed`, below kRestSpeedPerSize times the pieces'
    // spread when that is more).
    //
    // Each piece's centre between two recorded frames is measured against the rest speed, and how
    // far its farthest point got from where it was at the hold's first frame (|dx| + angle r)
    // against the rest speed times the hold. The recorded motion, not the velocities of the
    // frame's last step, and the turn over the hold, not between two frames: a piece resting on
    // others trembles in place (measured on the demo: a piece turning back and forth at 0.2 rad/s
    // for 2 s, 0.14 degrees in all).
    // A piece far from the others may move faster and still look still: a camera that keeps it in
    // view stands at least its distance d from the pieces' centre away (fov 40 degrees), where
    // kRestSpeedPerSize x d moves it under half a pixel a frame, and one that lets it go does not
    // see it. So each piece rests below the larger of the rest speed and kRestSpeedPerSize times
    // its distance from the dynamic pieces' centre of mass (a ball rolled 24 m from a 0.3 m object
    // ends its movie when the object's other pieces rest, not seconds later).
    // And no piece may gather speed over the hold (by more than kRestSpeed from its first frame to
    // its last): an object of hundreds of metres collapses under its own weight slowly at first,
    // below its size's rest speed.
    bool stayed(const Trajectory& t, uint32_t from, uint32_t to, double rest, bool landed);

private:
    // The dynamic pieces' centre of mass at frame g.
    Vec3 centre(const Trajectory& t, uint32_t g) const;
    // Piece i's speed between frames g - 1 and g (unit: m/s).
    double speed(const Trajectory& t, uint32_t g, uint32_t i) const;
    // Twice the distance from `c` within which the kRestSpreadMass of the mass nearest it lies at
    // frame g: once landed, the rest speed grows with the pieces' spread as it grows with the
    // object's size (a camera that frames pieces strewn over 2 m, as the follow camera frames the
    // 90% of the mass nearest its middle, sees a fragment creep at 5 cm/s under half a pixel a
    // frame).
    double spread(const Trajectory& t, uint32_t g, const Vec3& c);

    const BulletWorld& world_;
    const std::vector<double>& radius_;
    const double fps_;
    std::vector<double> mass_;  // each dynamic piece's; 0 for the others (unit: kg)
    std::vector<std::pair<double, double>> by_distance_;  // spread's scratch: (distance, mass)
};

}  // namespace shatter
