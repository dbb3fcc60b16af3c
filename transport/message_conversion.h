// Conversions between the LCM wire messages of lcmtypes/ and the plain sample
// structs of samples/samples.h, so the libraries never see an LCM type.
// Field for field, no unit changes: both sides use SI units and the same names.
#pragma once

#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/loadcell_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/motor_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/setpoint_t.hpp"
#include "birotor/strain_t.hpp"
#include "birotor/truth_t.hpp"
#include "samples/motor_command.h"
#include "samples/samples.h"
#include "samples/setpoint.h"

namespace birotor {

StrainSample FromMessage(const strain_t& message);
strain_t ToMessage(const StrainSample& sample);

MotorSample FromMessage(const motor_t& message);
motor_t ToMessage(const MotorSample& sample);

ImuSample FromMessage(const imu_t& message);
imu_t ToMessage(const ImuSample& sample);

PoseSample FromMessage(const pose_t& message);
pose_t ToMessage(const PoseSample& sample);

LoadCellSample FromMessage(const loadcell_t& message);
loadcell_t ToMessage(const LoadCellSample& sample);

TruthSample FromMessage(const truth_t& message);
truth_t ToMessage(const TruthSample& sample);

ForceEstimate FromMessage(const force_estimate_t& message);
force_estimate_t ToMessage(const ForceEstimate& estimate);

MotorCommand FromMessage(const motor_command_t& message);
motor_command_t ToMessage(const MotorCommand& command);

Setpoint FromMessage(const setpoint_t& message);
setpoint_t ToMessage(const Setpoint& setpoint);

}  // namespace birotor
