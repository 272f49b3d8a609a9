#include "kinetofem/verification/fe_probes.hpp"

#include <cmath>
#include <map>
#include <tuple>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/element_library.hpp"

namespace kinetofem::verification {
namespace {

// Face rules finer than the element library's (which are exact only for the
// stiffness): a traction of degree 2 times a quadratic shape function needs
// degree 4 on triangles. Triangle: Dunavant's 6-point degree-4 rule on the
// reference triangle (area 1/2); quadrilateral: 4 x 4 Gauss-Legendre (degree 7).
const std::vector<fem::QuadraturePoint>& probe_rule(fem::FaceType type) {
  static const std::vector<fem::QuadraturePoint> triangle = [] {
    std::vector<fem::QuadraturePoint> rule;
    const double a1 = 0.445948490915965, b1 = 1.0 - 2.0 * a1, w1 = 0.223381589678011 / 2.0;
    const double a2 = 0.091576213509771, b2 = 1.0 - 2.0 * a2, w2 = 0.109951743655322 / 2.0;
    for (auto [a, b, w] : {std::tuple{a1, b1, w1}, std::tuple{a2, b2, w2}}) {
      rule.push_back({Eigen::Vector3d(a, a, 0.0), w});
      rule.push_back({Eigen::Vector3d(b, a, 0.0), w});
      rule.push_back({Eigen::Vector3d(a, b, 0.0), w});
    }
    return rule;
  }();
  static const std::vector<fem::QuadraturePoint> quadrilateral = [] {
    const double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                         0.8611363115940526};
    const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                         0.3478548451374538};
    std::vector<fem::QuadraturePoint> rule;
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) rule.push_back({Eigen::Vector3d(x[i], x[j], 0.0), w[i] * w[j]});
    return rule;
  }();
  return (type == fem::FaceType::Tri3 || type == fem::FaceType::Tri6) ? triangle : quadrilateral;
}

// Calls visit(face nodes, N, x, n, dA) at every Gauss point of every face of a set.
template <typename Visit>
void for_each_face_point(const fem::Mesh& mesh, const std::string& face_set, Visit&& visit) {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (const auto& faces : mesh.face_set(face_set)) {
    const auto& rule = probe_rule(faces.type);
    for (fem::Index f = 0; f < faces.size(); ++f) {
      const auto face = faces.face(f);
      for (const auto& qp : rule) {
        fem::shape_functions(faces.type, qp.xi, N, dN);
        Eigen::Vector3d x = Eigen::Vector3d::Zero(), a1 = x, a2 = x;
        for (size_t i = 0; i < face.size(); ++i) {
          const Eigen::Vector3d xi = mesh.nodes.row(face[i]).transpose();
          x += N[Eigen::Index(i)] * xi;
          a1 += dN(Eigen::Index(i), 0) * xi;
          a2 += dN(Eigen::Index(i), 1) * xi;
        }
        const Eigen::Vector3d normal = a1.cross(a2);
        const double jacobian = normal.norm();
        require(jacobian > 0, "face set '{}': face {} is degenerate", face_set, f);
        visit(face, N, x, Eigen::Vector3d(normal / jacobian), jacobian * qp.weight);
      }
    }
  }
}

}  // namespace

std::vector<fem::NodalForce> consistent_face_forces(const fem::Mesh& mesh,
                                                    const std::string& face_set,
                                                    const TractionField& traction) {
  std::map<fem::Index, Eigen::Vector3d> force;
  for_each_face_point(mesh, face_set,
                      [&](std::span<const fem::Index> face, const Eigen::VectorXd& N,
                          const Eigen::Vector3d& x, const Eigen::Vector3d& n, double dA) {
                        const Eigen::Vector3d t = traction(x, n);
                        for (size_t i = 0; i < face.size(); ++i) {
                          auto [it, inserted] = force.try_emplace(face[i], Eigen::Vector3d::Zero());
                          it->second += N[Eigen::Index(i)] * dA * t;
                        }
                      });
  std::vector<fem::NodalForce> forces;
  forces.reserve(force.size());
  for (const auto& [node, f] : force) forces.push_back({node, f});
  return forces;
}

double face_integral(const fem::Mesh& mesh, const std::string& face_set,
                     const fem::DisplacementField& displacement, const SurfaceIntegrand& g) {
  double total = 0.0;
  for_each_face_point(mesh, face_set,
                      [&](std::span<const fem::Index> face, const Eigen::VectorXd& N,
                          const Eigen::Vector3d& x, const Eigen::Vector3d& n, double dA) {
                        Eigen::Vector3d u = Eigen::Vector3d::Zero();
                        for (size_t i = 0; i < face.size(); ++i)
                          u += N[Eigen::Index(i)] * displacement.row(face[i]).transpose();
                        total += g(x, n, u) * dA;
                      });
  return total;
}

std::vector<fem::Index> nodes_where(const fem::Mesh& mesh,
                                    const std::function<bool(const Eigen::Vector3d&)>& predicate) {
  std::vector<fem::Index> nodes;
  for (fem::Index n = 0; n < mesh.node_count(); ++n)
    if (predicate(mesh.nodes.row(n).transpose())) nodes.push_back(n);
  return nodes;
}

double observed_order(double coarse, double medium, double fine, double ratio) {
  return std::log(std::abs(coarse - medium) / std::abs(medium - fine)) / std::log(ratio);
}

std::vector<fem::DisplacementSupport> prescribe_field(
    const fem::Mesh& mesh, const std::vector<fem::Index>& nodes,
    const std::function<Eigen::Vector3d(const Eigen::Vector3d& x)>& u) {
  std::vector<fem::DisplacementSupport> supports;
  supports.reserve(nodes.size());
  for (fem::Index n : nodes) {
    fem::DisplacementSupport s;
    s.label = fmt::format("node {}", n);
    s.nodes = {n};
    s.value_m = u(mesh.nodes.row(n).transpose());
    supports.push_back(std::move(s));
  }
  return supports;
}

}  // namespace kinetofem::verification
