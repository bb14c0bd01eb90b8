#pragma once
// Runs a command line from a test: its exit status, stdout and stderr (test_contact_eval, test_bag_analyze).

// STL
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

// POSIX
#include <sys/wait.h>
#include <unistd.h>

namespace sphere_contact_estimator
{
namespace test
{
struct Outcome
{
  int status = -1;  ///< exit status; -1 if it did not exit normally
  std::string out, err;
};

inline std::string slurp(const std::string& path)
{
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

inline Outcome runCommand(const std::string& command)
{
  char out_path[] = "/tmp/sce_test_outXXXXXX";
  char err_path[] = "/tmp/sce_test_errXXXXXX";
  close(mkstemp(out_path));
  close(mkstemp(err_path));
  const int raw = std::system((command + " >" + out_path + " 2>" + err_path).c_str());
  Outcome r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out_path);
  r.err = slurp(err_path);
  std::remove(out_path);
  std::remove(err_path);
  return r;
}
}  // namespace test
}  // namespace sphere_contact_estimator
