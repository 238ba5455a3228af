#include "dlmfd/fluid/velocity_advection.h"

#include "dlmfd/fluid/advection_least_squares.h"
#include "dlmfd/fluid/advection_wave.h"

namespace dlmfd {

std::unique_ptr<VelocityAdvection> MakeVelocityAdvection(const Grid& grid, const Params& params,
                                                         const BoundaryData& boundary_data) {
  if (params.splitting.advection == AdvectionScheme::kLeastSquares) {
    return std::make_unique<AdvectionLeastSquares>(
        grid, params.domain, params.fluid, params.splitting.beta,
        params.splitting.steady_correction.value(), params.solvers, boundary_data);
  }
  return std::make_unique<AdvectionWave>(grid, params.domain, params.fluid, params.splitting.beta,
                                         params.splitting.steady_correction.value(), params.solvers,
                                         boundary_data);
}

}  // namespace dlmfd
