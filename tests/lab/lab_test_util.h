// tests/lab/lab_test_util.h — a lab server on an ephemeral loopback port for the API and fuzz
// tests, an httplib client for it, and reading a PNG answer back.
#pragma once

#include <gtest/gtest.h>
#include <httplib.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "apps/command_util.h"
#include "core/base/image.h"
#include "lab/lab_server.h"

namespace sl::test {

// Generous enough that no test meets the rate cap except the one that tests it.
constexpr double kTestRequestsPerSecond = 1e6;
constexpr int kTestBurst = 1000000;

inline std::unique_ptr<lab::LabServer> startLab(double rate = kTestRequestsPerSecond,
                                                int burst = kTestBurst, int* port = nullptr) {
  lab::LabOptions o;
  o.host = "127.0.0.1";
  o.port = 0;
  o.requestsPerSecond = rate;
  o.burst = burst;
  auto server = std::make_unique<lab::LabServer>(o);
  const int p = server->start();
  if (port) *port = p;
  return server;
}

// A PNG body decoded through a file (core/base/image.h reads PNGs from files).
inline Image decodePng(const std::string& body, const std::filesystem::path& dir,
                       const std::string& name) {
  const std::filesystem::path file = dir / name;
  std::ofstream(file, std::ios::binary) << body;
  return readPng(file.string());
}

}  // namespace sl::test
