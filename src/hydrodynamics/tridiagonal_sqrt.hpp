#pragma once
// The first column of the square root of a small symmetric tridiagonal matrix (the Lanczos
// solver's T, m x m with m ~ tens), on the host.
#include <vector>

namespace structmd {

// s = T^{1/2} e_1 for T with diagonal `diagonal` (m numbers) and off-diagonal `offDiagonal` (m - 1).
// Returns false where T has an eigenvalue <= 0 (the operator was not positive definite).
bool tridiagonal_sqrt_first_column(const std::vector<double>& diagonal, const std::vector<double>& offDiagonal,
                                   std::vector<double>& s);

}  // namespace structmd
