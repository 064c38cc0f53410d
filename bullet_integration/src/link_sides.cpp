// Link sides (link_sides.hpp).
#include "link_sides.hpp"

namespace patchspin::bullet::internal {
namespace {

// Fills the 6 rows of J for one link at O, `sign` times (S1), into `out`.
void fillLinkRows(const btMultiBodyLinkCollider& c, const Mat3& F, const Vec3& O, double rho,
                  double sign, btMultiBodyJacobianData& data, btScalar* out) {
  const btMultiBody& body = *c.m_multiBody;
  const int n = body.getNumDofs() + 6;
  const btVector3 o = toBt(O);
  const btVector3 ex = toBt(sign * F.col(0)), ey = toBt(sign * F.col(1));
  const btVector3 nz = toBt(sign * F.col(2)), spin = toBt(sign * rho * F.col(2));
  const btVector3 zero(0, 0, 0);
  // rows: n.u(O), ex.omega, ey.omega, ex.u(O), ey.u(O), rho n.omega
  const btVector3 ang[6] = {zero, ex, ey, zero, zero, spin};
  const btVector3 lin[6] = {nz, zero, zero, ex, ey, zero};
  for (int i = 0; i < 6; ++i)
    body.fillConstraintJacobianMultiDof(c.m_link, o, ang[i], lin[i], out + i * n, data.scratch_r,
                                        data.scratch_v, data.scratch_m);
}

}  // namespace

void setUpLinkSides(const PatchState& st, const btMultiBodyLinkCollider* const links[2],
                    const LinkArrays& arrays, LinkTerms& terms, ArticulatedShare& share) {
  Mat3 F;
  Vec3 O;
  patchFrameOf(st, F, O);
  const double rho = st.friction->rho();
  const bool same = links[0] && links[1] && links[0]->m_multiBody == links[1]->m_multiBody;
  for (int s = 0; s < 2; ++s) {
    if (!links[s] || (same && s == 1)) continue;
    btMultiBody* body = links[s]->m_multiBody;
    LinkSide& side = terms.side[s];
    side.body = body;
    side.link = links[s]->m_link;
    side.n = body->getNumDofs() + 6;
    side.sign = s == 0 ? 1.0 : -1.0;
    const std::size_t rows = std::size_t(6 * side.n);
    side.offset = arrays.jac.size();
    arrays.jac.resize(side.offset + rows);
    arrays.resp.resize(side.offset + rows);
    btScalar* J = &arrays.jac[side.offset];
    fillLinkRows(*links[s], F, O, rho, side.sign, arrays.data, J);
    if (same) {
      arrays.scratch.resize(rows);
      fillLinkRows(*links[1], F, O, rho, -1.0, arrays.data, arrays.scratch.data());
      for (std::size_t k = 0; k < rows; ++k) J[k] += arrays.scratch[k];
    }
    btScalar* R = &arrays.resp[side.offset];
    for (int i = 0; i < 6; ++i)
      body->calcAccelerationDeltasMultiDof(J + i * side.n, R + i * side.n, arrays.data.scratch_r,
                                           arrays.data.scratch_v);
    const btScalar* qdot = body->getVelocityVector();
    for (int i = 0; i < 6; ++i) {
      double c = 0.0;
      for (int k = 0; k < side.n; ++k) c += double(J[i * side.n + k]) * double(qdot[k]);
      terms.c0[i] += c;
      for (int j = 0; j < 6; ++j) {
        double kij = 0.0;
        for (int k = 0; k < side.n; ++k)
          kij += double(J[i * side.n + k]) * double(R[j * side.n + k]);
        share.K6(i, j) += kij;
      }
    }
    side.velocity = body->getCompanionId();
    if (side.velocity < 0) {
      side.velocity = arrays.data.m_deltaVelocities.size();
      body->setCompanionId(side.velocity);
      arrays.data.m_deltaVelocities.resize(side.velocity + side.n);
    }
  }
  // (J M^-1 J^T is symmetric: its round-off is not)
  share.K6 = 0.5 * (share.K6 + share.K6.transpose()).eval();
  share.before = terms.c0;
}

}  // namespace patchspin::bullet::internal
