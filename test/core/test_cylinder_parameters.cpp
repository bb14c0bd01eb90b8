// Non-physical parameters and speeds are rejected where they enter, with a message naming them.

// STL
#include <limits>
#include <string>

// GTest
#include <gtest/gtest.h>

// Package
#include "cylinder_test_support.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_model.h"
#include "sphere_contact_estimator/core/rolling_resistance/cylinder_table.h"

namespace sphere_contact_estimator
{
namespace
{
using test::paperParameters;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Expects every model kind to refuse p with a message that contains `symbol`.
void expectRejected(const CylinderParameters& p, const std::string& symbol)
{
  for (const CylinderModelKind kind : { CylinderModelKind::Exact, CylinderModelKind::Expansion, CylinderModelKind::Table })
  {
    try
    {
      makeCylinderModel(kind, p);
      ADD_FAILURE() << toString(kind) << " accepted a bad " << symbol;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("(" + symbol + ")"), std::string::npos) << e.what();
    }
  }
}

TEST(CylinderParameters, NonPhysicalValuesAreRejected)
{
  struct Case
  {
    double CylinderParameters::*field;
    const char* symbol;
    std::vector<double> bad;
  };
  const std::vector<Case> cases{
    { &CylinderParameters::R, "R", { 0.0, -0.1, kNaN, kInf } },
    { &CylinderParameters::M, "M", { 0.0, -1.0, kNaN, kInf } },
    { &CylinderParameters::k, "k", { 0.0, -1e7, kNaN, kInf } },
    { &CylinderParameters::gamma, "gamma", { -1.0, kNaN, kInf } },
    { &CylinderParameters::m, "m", { -1.0, kNaN, kInf } },
    { &CylinderParameters::g, "g", { 0.0, -9.81, kNaN } },
    { &CylinderParameters::L, "L", { 0.0, -1.0, kInf } },
  };
  for (const Case& c : cases)
    for (double value : c.bad)
    {
      CylinderParameters p = paperParameters();
      p.*c.field = value;
      expectRejected(p, c.symbol);
    }
}

TEST(CylinderParameters, OutsideTheSupportedRange)
{
  // Finite but absurd magnitudes are refused too: they would overflow intermediates of eq. 18.
  const std::vector<std::pair<double CylinderParameters::*, double>> cases{
    { &CylinderParameters::R, 1e7 },    { &CylinderParameters::R, 1e-10 },     { &CylinderParameters::M, 1e13 },
    { &CylinderParameters::k, 1e21 },   { &CylinderParameters::gamma, 1e-13 }, { &CylinderParameters::m, 1e13 },
    { &CylinderParameters::g, 1e7 },    { &CylinderParameters::L, 1e10 },
  };
  for (const auto& [field, value] : cases)
  {
    CylinderParameters p = paperParameters();
    p.*field = value;
    try
    {
      p.validate();
      ADD_FAILURE() << "accepted " << value;
    }
    catch (const std::invalid_argument& e)
    {
      EXPECT_NE(std::string(e.what()).find("supported range"), std::string::npos) << e.what();
    }
  }
}

TEST(CylinderParameters, BoundaryValuesAreAccepted)
{
  CylinderParameters p = paperParameters();
  p.gamma = 0.0;
  p.m = 0.0;
  EXPECT_NO_THROW(p.validate());
  p.R = CylinderParameters::kRangeR.hi;
  p.k = CylinderParameters::kRangeK.lo;
  EXPECT_NO_THROW(p.validate());
}

TEST(CylinderParameters, BadSpeedsAreRejected)
{
  for (const CylinderModelKind kind : { CylinderModelKind::Exact, CylinderModelKind::Expansion, CylinderModelKind::Table })
  {
    const auto model = makeCylinderModel(kind, paperParameters());
    for (double v : { -1e-12, -1.0, kNaN, kInf, -kInf, 3.0e8 })
      EXPECT_THROW(model->solve(v), std::invalid_argument) << toString(kind) << " v = " << v;
  }
}

TEST(CylinderParameters, TableArguments)
{
  EXPECT_THROW(CylinderTable(paperParameters(), 1), std::invalid_argument);
  EXPECT_THROW(CylinderTable(paperParameters(), 64, -1.0), std::invalid_argument);
  EXPECT_THROW(CylinderTable(paperParameters(), 64, kNaN), std::invalid_argument);
}

TEST(CylinderParameters, ModelNames)
{
  for (const CylinderModelKind kind : { CylinderModelKind::Exact, CylinderModelKind::Expansion, CylinderModelKind::Table })
    EXPECT_EQ(parseCylinderModelKind(toString(kind)), kind);
  EXPECT_FALSE(parseCylinderModelKind("Exact"));
  EXPECT_FALSE(parseCylinderModelKind(""));
}

}  // namespace
}  // namespace sphere_contact_estimator
