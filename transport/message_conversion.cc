// Field-by-field copies between wire messages and sample structs, through the
// one field list per type of transport/message_fields.h.
#include "transport/message_conversion.h"

#include "transport/message_fields.h"

namespace birotor {
namespace {

using internal::CopyForceFields;
using internal::CopyImuFields;
using internal::CopyLoadCellFields;
using internal::CopyMotorCommandFields;
using internal::CopyMotorFields;
using internal::CopyPoseFields;
using internal::CopySetpointFields;
using internal::CopyStrainFields;
using internal::CopyTruthFields;

// To{} zero-initialises the message's fields that the list does not name.
template <typename To, typename From>
To Converted(const From& from, void (*copy)(const From&, To*)) {
  To to{};
  copy(from, &to);
  return to;
}

}  // namespace

StrainSample FromMessage(const strain_t& m) { return Converted<StrainSample>(m, CopyStrainFields); }
strain_t ToMessage(const StrainSample& s) { return Converted<strain_t>(s, CopyStrainFields); }
MotorSample FromMessage(const motor_t& m) { return Converted<MotorSample>(m, CopyMotorFields); }
motor_t ToMessage(const MotorSample& s) { return Converted<motor_t>(s, CopyMotorFields); }
ImuSample FromMessage(const imu_t& m) { return Converted<ImuSample>(m, CopyImuFields); }
imu_t ToMessage(const ImuSample& s) { return Converted<imu_t>(s, CopyImuFields); }
PoseSample FromMessage(const pose_t& m) { return Converted<PoseSample>(m, CopyPoseFields); }
pose_t ToMessage(const PoseSample& s) { return Converted<pose_t>(s, CopyPoseFields); }
LoadCellSample FromMessage(const loadcell_t& m) { return Converted<LoadCellSample>(m, CopyLoadCellFields); }
loadcell_t ToMessage(const LoadCellSample& s) { return Converted<loadcell_t>(s, CopyLoadCellFields); }
TruthSample FromMessage(const truth_t& m) { return Converted<TruthSample>(m, CopyTruthFields); }
truth_t ToMessage(const TruthSample& s) { return Converted<truth_t>(s, CopyTruthFields); }
ForceEstimate FromMessage(const force_estimate_t& m) { return Converted<ForceEstimate>(m, CopyForceFields); }
force_estimate_t ToMessage(const ForceEstimate& e) { return Converted<force_estimate_t>(e, CopyForceFields); }

MotorCommand FromMessage(const motor_command_t& m) { return Converted<MotorCommand>(m, CopyMotorCommandFields); }
motor_command_t ToMessage(const MotorCommand& c) { return Converted<motor_command_t>(c, CopyMotorCommandFields); }
Setpoint FromMessage(const setpoint_t& m) { return Converted<Setpoint>(m, CopySetpointFields); }
setpoint_t ToMessage(const Setpoint& s) { return Converted<setpoint_t>(s, CopySetpointFields); }

}  // namespace birotor
