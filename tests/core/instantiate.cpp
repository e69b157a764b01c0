// Explicit instantiation of every core template for double and for the exact
// rational: every member must compile for both (the generic code has one body).
#include <qverify/batch/batch.hpp>
#include <qverify/core/core.hpp>
#include <qverify/exact/interval.hpp>
#include <qverify/exact/scalars.hpp>

#define QVERIFY_INSTANTIATE_CORE(S)                                                                          \
  namespace qverify {                                                                                        \
  template bool is_exact<S>();                                                                               \
  template S abs_of<S>(const S&);                                                                            \
  template int sign_of<S>(const S&);                                                                         \
  template Mat4<S> plane_pair<S>(const Vec4<S>&, const Vec4<S>&);                                            \
  template Mat4<S> centred_quadric<S>(const Mat3<S>&, const Vec3<S>&, const S&);                             \
  template Mat4<S> quadric_from_coefficients<S>(const S&, const S&, const S&, const S&, const S&, const S&,   \
                                                const S&, const S&, const S&, const S&);                     \
  template Mat4<S> sphere_quadric<S>(const Vec3<S>&, const S&);                                              \
  template Mat3<S> adjugate3<S>(const Mat3<S>&);                                                             \
  template Mat4<S> ellipsoid_quadric<S>(const Vec3<S>&, const Vec3<S>&, const Mat3<S>&);                     \
  template Mat4<S> cylinder_quadric<S>(const Vec3<S>&, const Vec3<S>&, const S&);                            \
  template Mat4<S> cone_quadric<S>(const Vec3<S>&, const Vec3<S>&, const S&);                                \
  template S minor3<S>(const Mat4<S>&, const int[3], const int[3]);                                          \
  template Mat4<S> adjugate4<S>(const Mat4<S>&);                                                             \
  template Truth degenerate_quadric<S>(const Mat4<S>&);                                                      \
  template Truth light_on_surface<S>(const Mat4<S>&, const Vec4<S>&);                                        \
  template Truth silhouette_empty<S>(const Mat4<S>&, const Vec4<S>&);                                        \
  template StatusDecision shadow_status<S>(const Mat4<S>&, const Vec4<S>&);                                  \
  template Truth reflection_degenerate<S>(const Mat4<S>&);                                                   \
  template Eigen::Matrix<S, 4, 3> plane_basis<S>(const Vec4<S>&);                                           \
  template Mat3<S> conic_on_plane<S>(const Mat4<S>&, const Vec4<S>&);                                        \
  template Truth conic_definite<S>(const Mat3<S>&);                                                          \
  template std::optional<int> definiteness<S, 2>(const Eigen::Matrix<S, 2, 2>&);                                \
  template std::optional<int> definiteness<S, 4>(const Mat4<S>&);                                            \
  template bool is_symmetric<S>(const Mat4<S>&, const S&);                                                   \
  template Vec4<S> polar_plane<S>(const Mat4<S>&, const Vec4<S>&);                                           \
  template Mat4<S> tangent_cone<S>(const Mat4<S>&, const Vec4<S>&);                                          \
  template Mat4<S> tangent_cone_from_polar<S>(const Mat4<S>&, const Vec4<S>&, const Vec4<S>&);               \
  template Mat4<S> terminator_quadric_from_polar<S>(const Vec4<S>&, const Vec4<S>&);                         \
  template Mat4<S> scaled_mirror_matrix<S>(const Vec4<S>&);                                                   \
  template Mat4<S> mirror_image_of_plane<S>(const Mat4<S>&, const Vec4<S>&);                                  \
  template Vec4<S> mirror_half_direction<S>(const Vec4<S>&);                                                        \
  template Mat4<S> mirror_matrix_from<S>(const Vec4<S>&, const Vec4<S>&);                                      \
  template Mat4<S> mirror_image_from<S>(const Mat4<S>&, const Vec4<S>&, const Vec4<S>&);                        \
  template S ordered_dot<S, 4>(const Vec4<S>&, const Vec4<S>&);                                                \
  template Vec4<S> ordered_product<S>(const Mat4<S>&, const Vec4<S>&);                                         \
  template ReflectionResult<S> reflection_in_plane<S>(const Mat4<S>&, const Vec4<S>&, Method);                 \
  template Mat4<S> gather_sym<S>(const SymBatch<S>&, Eigen::Index);                                            \
  template void scatter_sym<S>(SymBatch<S>&, Eigen::Index, const Mat4<S>&);                                    \
  template Mat4<S> load_sym_lanes<ScalarLanes<S>>(const S*);                                                  \
  template void store_sym_lanes<ScalarLanes<S>>(S*, const Mat4<S>&);                                           \
  template void store_vec4_lanes<ScalarLanes<S>>(S*, const Vec4<S>&);                                          \
  template void shadow_batch<S>(const SymBatch<S>&, const Vec4Batch<S>&, Method, SymBatch<S>&, Vec4Batch<S>&, \
                                SymBatch<S>&, int);                                                           \
  template void reflection_batch<S>(const SymBatch<S>&, const Vec4Batch<S>&, Method, AffineBatch<S>&,          \
                                    SymBatch<S>&, int);                                                       \
  template Vec4<S> frame_plane<S>(const Vec4<S>&);                                                           \
  template Mat4<S> terminator_quadric<S>(const Mat4<S>&, const Vec4<S>&);                                    \
  template struct PaperFrame<S>;                                                                             \
  template PaperFrame<S> paper_frame<S>(const Vec4<S>&);                                                     \
  template Mat4<S> paper_C<S>(const Mat4<S>&, const PaperFrame<S>&);                                         \
  template Mat4<S> paper_D<S>(const Mat4<S>&);                                                               \
  template Mat4<S> paper_P<S>(const Mat4<S>&, const PaperFrame<S>&);                                         \
  template Vec4<S> paper_S<S>(const Mat4<S>&);                                                               \
  template Vec4<S> paper_polar_plane<S>(const Vec4<S>&, const PaperFrame<S>&);                               \
  template Mat4<S> paper_R<S>(const Vec4<S>&, const PaperFrame<S>&);                                         \
  template struct PaperIntermediates<S>;                                                                     \
  template struct ShadowResult<S>;                                                                           \
  template unsigned shadow_flags<S>(const Mat4<S>&, const Vec4<S>&);                                         \
  template ShadowResult<S> shadow<S>(const Mat4<S>&, const Vec4<S>&, Method);                                \
  template Mat4<S> mirror_matrix<S>(const Vec4<S>&);                                                         \
  template Mat4<S> mirror_image<S>(const Mat4<S>&, const Mat4<S>&);                                          \
  template Mat4<S> mirror_image_paper<S>(const Mat4<S>&, const Mat4<S>&);                                    \
  template struct ReflectionResult<S>;                                                                       \
  template ReflectionResult<S> reflection<S>(const Mat4<S>&, const Mat4<S>&, Method);                        \
  template S cross_residual(const Eigen::MatrixBase<Mat4<S>>&, const Eigen::MatrixBase<Mat4<S>>&);           \
  template bool proportional(const Eigen::MatrixBase<Mat4<S>>&, const Eigen::MatrixBase<Mat4<S>>&, Factor,   \
                             const S&);                                                                      \
  }

QVERIFY_INSTANTIATE_CORE(double)
QVERIFY_INSTANTIATE_CORE(qverify::Rational)

// The formulas the batch runs on SIMD packs (batch/pack.hpp, exact/interval_pack.hpp): the
// direct route, instantiated for every pack type.
#define QVERIFY_INSTANTIATE_PACKED(S)                                                                        \
  namespace qverify {                                                                                        \
  template Vec4<S> polar_plane<S>(const Mat4<S>&, const Vec4<S>&);                                           \
  template Mat4<S> tangent_cone<S>(const Mat4<S>&, const Vec4<S>&);                                          \
  template Mat4<S> tangent_cone_from_polar<S>(const Mat4<S>&, const Vec4<S>&, const Vec4<S>&);               \
  template Vec4<S> frame_plane<S>(const Vec4<S>&);                                                           \
  template Mat4<S> terminator_quadric<S>(const Mat4<S>&, const Vec4<S>&);                                    \
  template Mat4<S> terminator_quadric_from_polar<S>(const Vec4<S>&, const Vec4<S>&);                         \
  template Vec4<S> mirror_half_direction<S>(const Vec4<S>&);                                                      \
  template Mat4<S> mirror_matrix<S>(const Vec4<S>&);                                                         \
  template Mat4<S> mirror_matrix_from<S>(const Vec4<S>&, const Vec4<S>&);                                    \
  template Mat4<S> mirror_image_from<S>(const Mat4<S>&, const Vec4<S>&, const Vec4<S>&);                      \
  template Mat4<S> mirror_image_of_plane<S>(const Mat4<S>&, const Vec4<S>&);                                 \
  template Mat4<S> mirror_image<S>(const Mat4<S>&, const Mat4<S>&);                                          \
  }

QVERIFY_INSTANTIATE_PACKED(qverify::DoublePack)
QVERIFY_INSTANTIATE_PACKED(qverify::IntervalPack)
