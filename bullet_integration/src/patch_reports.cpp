// Patch reports (patch_reports.hpp).
#include "patch_reports.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>

#include <algorithm>

namespace patchspin::bullet::internal {

void PatchReports::beginStep() {
  count_ = 0;
  filled_ = false;
  inStep_ = true;
}

void PatchReports::record(const PatchConstraint& pc, const Vec6& c) {
  if (count_ == sources_.size()) sources_.emplace_back();
  ReportSource& r = sources_[count_++];
  r.state = pc.state;
  r.model = pc.fb.model;
  r.sticking = pc.fb.sticking;
  r.mu = pc.fb.mu;
  r.rho = pc.fb.rho;
  r.dt = pc.fb.dt;
  r.lamN = pc.lamN;
  r.lamF = pc.lamF;
  r.slip = c.tail<3>();
}

void PatchReports::append(const PatchReports& other) {
  if (sources_.size() < count_ + other.count_) sources_.resize(count_ + other.count_);
  std::copy(other.sources_.begin(), other.sources_.begin() + std::ptrdiff_t(other.count_),
            sources_.begin() + std::ptrdiff_t(count_));
  count_ += other.count_;
}

void PatchReports::orderByBodies() {
  std::stable_sort(sources_.begin(), sources_.begin() + std::ptrdiff_t(count_),
                   [](const ReportSource& x, const ReportSource& y) {
                     const int bx = x.state->body->getWorldArrayIndex();
                     const int by = y.state->body->getWorldArrayIndex();
                     if (bx != by) return bx < by;
                     return x.state->other->getWorldArrayIndex() <
                            y.state->other->getWorldArrayIndex();
                   });
}

const std::vector<PatchReport>& PatchReports::reports() {
  fill();
  return reports_;
}

const PatchReport* PatchReports::find(const btCollisionObject* body) {
  fill();
  for (const PatchReport& r : reports_)
    if (r.body == body) return &r;
  return nullptr;
}

// Loads and wrench are the step's impulses over dt (Eq. (94) loads from the
// normal block: parts::toLoads).
void PatchReports::fill() {
  if (filled_ || inStep_) return;
  filled_ = true;
  if (reports_.size() < count_) {
    reports_.resize(count_);
    shapeIds_.resize(count_, 0);
  }
  for (std::size_t slot = 0; slot < count_; ++slot) {
    const ReportSource& src = sources_[slot];
    const PatchState& st = *src.state;
    PatchReport& r = reports_[slot];
    r.body = st.body;
    r.other = st.other;
    r.bodyChild = st.bodyChild;
    r.otherChild = st.otherChild;
    r.origin = st.geometry.origin;
    r.normal = st.geometry.normal;
    r.xAxis = st.geometry.xAxis;
    r.yAxis = st.geometry.yAxis;
    const PatchShape& shape = st.friction->shape();
    if (shapeIds_[slot] != st.shapeId || !r.shape) {
      r.shape = shape;
      shapeIds_[slot] = st.shapeId;
    }
    r.model = src.model;
    r.mu = src.mu;
    r.rho = src.rho;
    const PatchLoads l = parts::toLoads(src.lamN);
    r.loads = PatchLoads{l.Pz / src.dt, l.Tx / src.dt, l.Ty / src.dt};
    r.pressure = r.loads.Pz > 0.0 ? LinearPressure::fromLoads(shape, r.loads) : LinearPressure();
    r.Q = src.lamF / src.dt;
    r.slip = src.slip;
    r.r = r.slip.norm();
    r.sticking = src.sticking;
    r.w = src.sticking || r.r == 0.0 ? Vec3::Zero() : Vec3(r.slip / r.r);
  }
  reports_.resize(count_);
  shapeIds_.resize(count_);
}

}  // namespace patchspin::bullet::internal
