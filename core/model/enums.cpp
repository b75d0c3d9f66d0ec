#include "core/model/enums.h"

#include <array>
#include <utility>

namespace superdex {
namespace {

template <typename E, size_t N>
using Table = std::array<std::pair<E, const char*>, N>;

constexpr Table<ColliderType, 8> kColliderTypes{{{ColliderType::Auto, "Auto"},
                                                 {ColliderType::None, "None"},
                                                 {ColliderType::Sphere, "Sphere"},
                                                 {ColliderType::Box, "Box"},
                                                 {ColliderType::Plane, "Plane"},
                                                 {ColliderType::Mesh, "Mesh"},
                                                 {ColliderType::Sdf, "Sdf"},
                                                 {ColliderType::PointCloud, "PointCloud"}}};
constexpr Table<IntegrationMethod, 8> kMethods{
    {{IntegrationMethod::BackwardEuler, "BackwardEuler"},
     {IntegrationMethod::BDF2, "BDF2"},
     {IntegrationMethod::BDF3, "BDF3"},
     {IntegrationMethod::DIRK22, "DIRK22"},
     {IntegrationMethod::DIRK23, "DIRK23"},
     {IntegrationMethod::DIRK33, "DIRK33"},
     {IntegrationMethod::SymplecticDIRK12, "SymplecticDIRK12"},
     {IntegrationMethod::SymplecticDIRK22, "SymplecticDIRK22"}}};
constexpr Table<ActorBoundaryElementType, 6> kElements{
    {{ActorBoundaryElementType::P1Q1, "P1Q1"},
     {ActorBoundaryElementType::P1Q3, "P1Q3"},
     {ActorBoundaryElementType::P1Q6, "P1Q6"},
     {ActorBoundaryElementType::ExperimentalP1Q7, "ExperimentalP1Q7"},
     {ActorBoundaryElementType::ExperimentalP1Q12, "ExperimentalP1Q12"},
     {ActorBoundaryElementType::ExperimentalP1Q16, "ExperimentalP1Q16"}}};

template <typename E, size_t N>
const char* Name(const Table<E, N>& t, E v) {
  for (const auto& [e, name] : t)
    if (e == v) return name;
  return "?";
}
template <typename E, size_t N>
bool Find(const Table<E, N>& t, const std::string& s, E* v) {
  for (const auto& [e, name] : t)
    if (s == name) {
      *v = e;
      return true;
    }
  return false;
}
template <typename E, size_t N>
std::string Names(const Table<E, N>& t) {
  std::string out;
  for (const auto& [e, name] : t) out += (out.empty() ? "" : ", ") + std::string(name);
  return out;
}

}  // namespace

const char* ToString(ColliderType v) { return Name(kColliderTypes, v); }
const char* ToString(IntegrationMethod v) { return Name(kMethods, v); }
const char* ToString(ActorBoundaryElementType v) { return Name(kElements, v); }
const char* ToString(IncludeNestedActors v) { return v == IncludeNestedActors::Yes ? "Yes" : "No"; }
bool Parse(const std::string& s, ColliderType* v) { return Find(kColliderTypes, s, v); }
bool Parse(const std::string& s, IntegrationMethod* v) { return Find(kMethods, s, v); }
bool Parse(const std::string& s, ActorBoundaryElementType* v) { return Find(kElements, s, v); }
std::string AllNames(ColliderType) { return Names(kColliderTypes); }
std::string AllNames(IntegrationMethod) { return Names(kMethods); }
std::string AllNames(ActorBoundaryElementType) { return Names(kElements); }

}  // namespace superdex
