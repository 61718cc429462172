#include "millsim/devices/HandDevice.h"

#include <cmath>

#include "millsim/devices/TrajectoryDevice.h"

namespace millsim {

const NodeType& HandDevice::type() {
  static const NodeType t = makeNodeType<HandDevice>(
      "HandDevice", "children", "MillSim devices",
      "A simulated hand (mass, damping, stiffness) holding a simulated device, pulled along a trajectory and "
      "pushed back by the rendered force and torque: closed loop, for stability tests and headless lessons.");
  return t;
}

void HandDevice::initialize(DiagnosticSink& sink) {
  HapticsDevice::initialize(sink);
  trajectory_ = loadDeviceTrajectory(*this, url.get(), sink);
}

HandModel HandDevice::model() const {
  HandModel m;
  m.handMass = handMass.get();
  m.handDamping = handDamping.get();
  m.handStiffness = handStiffness.get();
  m.handInertia = handInertia.get();
  m.handAngularDamping = handAngularDamping.get();
  m.handAngularStiffness = handAngularStiffness.get();
  m.deviceMass = deviceMass.get();
  m.deviceDamping = deviceDamping.get();
  m.deviceInertia = deviceInertia.get();
  m.deviceAngularDamping = deviceAngularDamping.get();
  m.releaseTime = releaseTime.get();
  m.outputHold = outputHold.get();
  return m;
}

namespace {

// Rotation vector (axis × angle, |angle| ≤ π) of a unit quaternion.
glm::dvec3 rotationVector(glm::dquat q) {
  if (q.w < 0.0) q = -q;
  const glm::dvec3 v(q.x, q.y, q.z);
  const double s = glm::length(v);
  if (s < 1e-12) return 2.0 * v;  // small angle: 2·sin(θ/2)·axis ≈ θ·axis
  return v * (2.0 * std::atan2(s, q.w) / s);
}

glm::dquat fromRotationVector(const glm::dvec3& r) {
  const double angle = glm::length(r);
  if (angle < 1e-12) return glm::normalize(glm::dquat(1.0, 0.5 * r.x, 0.5 * r.y, 0.5 * r.z));
  return glm::angleAxis(angle, r / angle);
}

class HandDriver final : public DeviceDriver {
public:
  HandDriver(Trajectory trajectory, const HandModel& model, bool loop)
      : trajectory_(std::move(trajectory)), model_(model), loop_(loop) {}

  DeviceReading read(double t, double) override {
    const TrajectorySample ref = reference(t);
    if (!started_) {
      // The hand starts at rest, holding the device at the reference.
      started_ = true;
      pose_ = ref.pose;
      previousRef_ = ref.pose;
      previousT_ = t;
      return {pose_, ref.button, true};
    }
    const double h = t - previousT_;
    const bool released = t >= model_.releaseTime && model_.releaseTime >= 0.0;
    // The device drops the last wrench outputHold after it was sent (only
    // after a stall of the loop: a frame sends a new one every period).
    const double drop = sentAt_ + model_.outputHold;
    if (h > 0.0 && drop < t) {
      if (drop > previousT_) {  // held for the first part of this step
        const TrajectorySample mid = reference(drop);
        integrate(mid.pose, drop - previousT_, released);
        previousRef_ = mid.pose;
        previousT_ = drop;
      }
      force_ = torque_ = glm::dvec3(0.0);
    }
    if (t - previousT_ > 0.0) integrate(ref.pose, t - previousT_, released);
    previousRef_ = ref.pose;
    previousT_ = t;
    return {pose_, ref.button, true};
  }

  void write(const glm::dvec3& force, const glm::dvec3& torque) override {
    force_ = force;
    torque_ = torque;
    sentAt_ = previousT_;  // written in the frame of the last read
  }
  double naturalDuration() const override {
    return loop_ ? DeviceDriver::naturalDuration() : trajectory_.endTime() - trajectory_.startTime();
  }

private:
  TrajectorySample reference(double t) const {
    const double start = trajectory_.startTime(), length = trajectory_.endTime() - start;
    const double local = loop_ && length > 0.0 ? std::fmod(std::max(t, 0.0), length) : t;
    return trajectory_.at(start + local);
  }

  // One step of m·v̇ = K(r − x) + B(ṙ − v) − b·v + F, translation and
  // rotation alike, with the linear terms at the step's midpoint (the
  // trapezoidal rule): unconditionally stable, and for the spring neither
  // adding nor removing energy, so all dissipation is the physical damping B
  // and b (backward Euler would damp numerically and flatter a renderer's
  // stability). The rendered wrench is held from the last frame.
  void integrate(const Pose& ref, double h, bool released) {
    const HandModel& m = model_;
    const double handM = released ? 0.0 : m.handMass, handB = released ? 0.0 : m.handDamping,
                 handK = released ? 0.0 : m.handStiffness;
    const double mass = handM + m.deviceMass, damping = handB + m.deviceDamping;
    const glm::dvec3 refVelocity = (ref.position - previousRef_.position) / h;
    const glm::dvec3 refMid = 0.5 * (ref.position + previousRef_.position);
    const glm::dvec3 rhs = mass * velocity_ + h * (handK * (refMid - pose_.position) + handB * refVelocity + force_) -
                           (0.25 * h * h * handK + 0.5 * h * damping) * velocity_;
    const glm::dvec3 v = rhs / (mass + 0.25 * h * h * handK + 0.5 * h * damping);
    pose_.position += 0.5 * h * (velocity_ + v);
    velocity_ = v;

    const double handI = released ? 0.0 : m.handInertia, handBr = released ? 0.0 : m.handAngularDamping,
                 handKr = released ? 0.0 : m.handAngularStiffness;
    const double inertia = handI + m.deviceInertia, dampingR = handBr + m.deviceAngularDamping;
    const glm::dquat refStep = ref.orientation * glm::conjugate(previousRef_.orientation);
    const glm::dvec3 refOmega = rotationVector(refStep) / h;
    // The reference halfway through the step, and the error towards it.
    const glm::dquat refMidQ = fromRotationVector(0.5 * rotationVector(refStep)) * previousRef_.orientation;
    const glm::dvec3 error = rotationVector(refMidQ * glm::conjugate(pose_.orientation));
    const glm::dvec3 rhsR = inertia * omega_ + h * (handKr * error + handBr * refOmega + torque_) -
                            (0.25 * h * h * handKr + 0.5 * h * dampingR) * omega_;
    const glm::dvec3 w = rhsR / (inertia + 0.25 * h * h * handKr + 0.5 * h * dampingR);
    pose_.orientation = glm::normalize(fromRotationVector(0.5 * h * (omega_ + w)) * pose_.orientation);
    omega_ = w;
  }

  Trajectory trajectory_;
  HandModel model_;
  bool loop_;
  bool started_ = false;
  Pose pose_, previousRef_;
  double previousT_ = 0.0;
  double sentAt_ = 0.0;  // when the held wrench was written
  glm::dvec3 velocity_{0.0}, omega_{0.0};
  glm::dvec3 force_{0.0}, torque_{0.0};
};

}  // namespace

std::unique_ptr<DeviceDriver> makeHandDriver(Trajectory trajectory, const HandModel& model, bool loop) {
  return std::make_unique<HandDriver>(std::move(trajectory), model, loop);
}

std::unique_ptr<DeviceDriver> HandDevice::openDriver(const DriverOptions& options) const {
  if (options.trajectory) return makeHandDriver(*options.trajectory, model(), loop.get());
  if (!trajectory_)
    throw DeviceError("HandDevice" + (defName().empty() ? std::string() : " '" + defName() + "'") +
                      " has no trajectory for the hand to follow: set its url or pass --trajectory");
  return makeHandDriver(*trajectory_, model(), loop.get());
}

}  // namespace millsim
