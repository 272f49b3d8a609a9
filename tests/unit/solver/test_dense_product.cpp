// fem::blas_product (BLAS dgemm) against Eigen's product: blocks with outer
// strides, beta = 0 and 1, empty inner dimension, wrong sizes. Reference:
// Eigen's own product, 1e-13 relative (the same sums in another order).
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/dense_product.hpp"

namespace kinetofem::fem {
namespace {

TEST(BlasProduct, EqualsEigensProductOnBlocks) {
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(301, 17), b = Eigen::MatrixXd::Random(17, 40);
  Eigen::MatrixXd c = Eigen::MatrixXd::Random(301, 40);
  const Eigen::MatrixXd c0 = c;
  blas_product(a, b.middleCols(5, 20), c.leftCols(20));
  EXPECT_LT((c.leftCols(20) - a * b.middleCols(5, 20)).norm(), 1e-13 * (a * b).norm());
  EXPECT_EQ(c.rightCols(20), c0.rightCols(20));  // untouched
  blas_product(a, b, c, 1.0);
  EXPECT_LT((c.rightCols(20) - (c0.rightCols(20) + a * b.rightCols(20))).norm(), 1e-13 * (a * b).norm());
}

TEST(BlasProduct, EmptyInnerDimensionScalesByBeta) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Ones(3, 2);
  blas_product(Eigen::MatrixXd(3, 0), Eigen::MatrixXd(0, 2), c, 0.0);
  EXPECT_EQ(c, Eigen::MatrixXd::Zero(3, 2));
}

TEST(BlasProduct, SizesThatDoNotFitAreAnError) {
  Eigen::MatrixXd c(3, 2);
  EXPECT_THROW(blas_product(Eigen::MatrixXd(3, 4), Eigen::MatrixXd(5, 2), c), Error);
}

}  // namespace
}  // namespace kinetofem::fem
