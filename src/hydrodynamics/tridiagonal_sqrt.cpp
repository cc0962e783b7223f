#include "hydrodynamics/tridiagonal_sqrt.hpp"

#include <Eigen/Eigenvalues>

namespace structmd {

bool tridiagonal_sqrt_first_column(const std::vector<double>& diagonal, const std::vector<double>& offDiagonal,
                                   std::vector<double>& s) {
    const Eigen::Index m = static_cast<Eigen::Index>(diagonal.size());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen;
    eigen.computeFromTridiagonal(Eigen::Map<const Eigen::VectorXd>(diagonal.data(), m),
                                 Eigen::Map<const Eigen::VectorXd>(offDiagonal.data(), m - 1), Eigen::ComputeEigenvectors);
    if (eigen.info() != Eigen::Success || !(eigen.eigenvalues().minCoeff() > 0.0)) return false;
    // T^{1/2} e_1 = Q diag(sqrt(lambda)) Q^T e_1, and Q^T e_1 is Q's first row.
    const Eigen::MatrixXd& q = eigen.eigenvectors();
    const Eigen::VectorXd column = q * (eigen.eigenvalues().cwiseSqrt().cwiseProduct(q.row(0).transpose()));
    s.assign(column.data(), column.data() + m);
    return true;
}

}  // namespace structmd
