#include "millsim/run/FrameLog.h"

#include "millsim/core/FieldValues.h"

namespace millsim {

const char* frameLogHeader() {
  return "t,x,y,z,qw,qx,qy,qz,fx,fy,fz,tx,ty,tz,contacts,frame_us,"
         "draw_x,draw_y,draw_z,draw_qw,draw_qx,draw_qy,draw_qz,proxy_x,proxy_y,proxy_z,ip_x,ip_y,ip_z,"
         "button,removed_mm3,flags,period_us,renderer,tool\n";
}

void appendFrameRow(std::string& out, const FrameRecord& r) {
  auto num = [&out](double v) {
    out += formatNumber(v);
    out += ',';
  };
  const HapticOutput& o = r.out;
  num(r.t);
  for (double v : {r.device.position.x, r.device.position.y, r.device.position.z}) num(v);
  for (double v : {r.device.orientation.w, r.device.orientation.x, r.device.orientation.y, r.device.orientation.z})
    num(v);
  for (double v : {r.force.x, r.force.y, r.force.z, r.torque.x, r.torque.y, r.torque.z}) num(v);
  out += std::to_string(o.contacts) + ',';
  num(r.computeUs);
  const Pose& d = o.drawnTool;
  for (double v : {d.position.x, d.position.y, d.position.z, d.orientation.w, d.orientation.x, d.orientation.y,
                   d.orientation.z})
    num(v);
  for (double v : {o.proxy.x, o.proxy.y, o.proxy.z, o.intersection.x, o.intersection.y, o.intersection.z}) num(v);
  out += r.button ? "1," : "0,";
  num(r.removedVolume * 1e9);
  out += std::to_string(o.flags) + ',';
  out += formatNumber(r.periodUs);
  out += ',';
  out += r.renderer;
  out += ',';
  out += toolCell(r.tool);
  out += '\n';
}

FrameLogWriter::FrameLogWriter(std::ostream* out) : out_(out) {
  if (out_) *out_ << frameLogHeader();
}

std::size_t FrameLogWriter::drain(HapticLoop& loop) {
  return loop.records().drain([this](const FrameRecord& r) {
    last_ = r;
    ++written_;
    for (const auto& observer : observers_) observer(r);
    if (!out_) return;
    row_.clear();
    appendFrameRow(row_, r);
    *out_ << row_;
  });
}

}  // namespace millsim
