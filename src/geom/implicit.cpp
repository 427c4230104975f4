// Decided predicates on implicit points (implicit.h): each sign is the polynomial's,
// through filtered.h's decide (Fp, then Dd, then exact), times the signs of the W's.
#include "cellforge/geom/implicit.h"

#include <limits>

namespace cellforge::inline geom {

ImplicitPoint ImplicitPoint::at(Vec3 x) {
  ImplicitPoint r;
  r.p[0] = x;
  return r;
}

ImplicitPoint ImplicitPoint::segment_plane(Vec3 p, Vec3 q, const PlanePoints& plane) {
  ImplicitPoint r;
  r.kind = Kind::kLpi;
  r.p[0] = p;
  r.p[1] = q;
  r.p[2] = plane.a;
  r.p[3] = plane.b;
  r.p[4] = plane.c;
  return r;
}

ImplicitPoint ImplicitPoint::three_planes(const PlanePoints& a, const PlanePoints& b,
                                          const PlanePoints& c) {
  ImplicitPoint r;
  r.kind = Kind::kTpi;
  r.p = {a.a, a.b, a.c, b.a, b.b, b.c, c.a, c.b, c.c};
  return r;
}

namespace {

int w_sign(const ImplicitPoint& x) {
  if (x.kind == ImplicitPoint::Kind::kExplicit) return 1;
  return decide([&]<class T>() { return x.eval<T>().c[3]; });
}

}  // namespace

bool is_defined(const ImplicitPoint& x) { return w_sign(x) != 0; }

Vec3 approx(const ImplicitPoint& x) {
  if (x.kind == ImplicitPoint::Kind::kExplicit) return x.p[0];
  const H3<Fp> f = x.eval<Fp>();
  bool sharp = f.c[3].e <= std::abs(f.c[3].v) * 0x1p-45;  // W, and every X, to 45 bits
  for (int i = 0; i < 3; ++i) sharp = sharp && f.c[i].e <= std::abs(f.c[i].v) * 0x1p-45;
  if (sharp && f.c[3].v != 0)
    return {f.c[0].v / f.c[3].v, f.c[1].v / f.c[3].v, f.c[2].v / f.c[3].v};
  const H3<Dyadic> h = x.eval<Dyadic>();
  if (h.c[3].sign() == 0) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan};
  }
  const double w = h.c[3].to_double();
  return {h.c[0].to_double() / w, h.c[1].to_double() / w, h.c[2].to_double() / w};
}

int orient3d(Vec3 a, Vec3 b, Vec3 c, const ImplicitPoint& x) {
  const int w = w_sign(x);
  if (w == 0) return 0;
  return w * decide([&]<class T>() { return plane_side_poly<T>(a, b, c, x.eval<T>()); });
}

int orient2d_projected(const ImplicitPoint& a, const ImplicitPoint& b, const ImplicitPoint& c,
                       int drop_axis) {
  const int w = w_sign(a) * w_sign(b) * w_sign(c);
  if (w == 0) return 0;
  return w * decide([&]<class T>() {
           return orient2_poly(projected(a.eval<T>(), drop_axis), projected(b.eval<T>(), drop_axis),
                               projected(c.eval<T>(), drop_axis));
         });
}

int compare(const ImplicitPoint& x, const ImplicitPoint& y, int axis) {
  const int w = w_sign(x) * w_sign(y);
  if (w == 0) return 0;
  return w * decide([&]<class T>() { return compare_poly(x.eval<T>(), y.eval<T>(), axis); });
}

int compare_along(const ImplicitPoint& x, const ImplicitPoint& y, Vec3 p, Vec3 q) {
  const int w = w_sign(x) * w_sign(y);
  if (w == 0) return 0;
  // (Y/Wy - X/Wx).d = (Y Wx - X Wy).d / (Wx Wy)
  return w * decide([&]<class T>() {
           const H3<T> X = x.eval<T>(), Y = y.eval<T>();
           const V3<T> d = sub(vec<T>(q), vec<T>(p));
           T s = T(0.0);
           for (int i = 0; i < 3; ++i) s = s + (Y.c[i] * X.c[3] - X.c[i] * Y.c[3]) * d[i];
           return s;
         });
}

bool same_point(const ImplicitPoint& x, const ImplicitPoint& y) {
  if (w_sign(x) == 0 || w_sign(y) == 0) return false;
  for (int axis = 0; axis < 3; ++axis)
    if (compare(x, y, axis) != 0) return false;
  return true;
}

}  // namespace cellforge::inline geom
