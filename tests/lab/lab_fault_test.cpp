// The live lab under an injected GL fault (core/gl/gl_fault.h): the request that meets it answers
// 500 with the one-line GL error naming the fault and its pass, and the next request renders
// the same frame as before the fault (the failed context is dropped and made afresh).
#include <gtest/gtest.h>

#include "core/gl/gl_fault.h"
#include "lab_test_util.h"

namespace sl::test {
namespace {

class LabFault : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = startLab(kTestRequestsPerSecond, kTestBurst, &port_);
    client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
    client_->set_read_timeout(120, 0);
  }
  void TearDown() override { clearGlFault(); }
  httplib::Result get(const std::string& path) { return client_->Get(path.c_str()); }

  std::unique_ptr<lab::LabServer> server_;
  std::unique_ptr<httplib::Client> client_;
  int port_ = 0;
};

struct Case {
  std::string query;  // a frame of one technique
  std::string fault;  // SHADOWLAB_INJECT_GL_FAULT's spelling
  std::string pass;   // the pass the fault falls in
};

TEST_F(LabFault, AFaultAnswers500AndTheNextRequestRendersTheSameFrame) {
  const auto dir = testDir("lab", true);
  const std::vector<Case> cases = {
      {"scene=brabec&technique=modern.hw&size=96x72", "error@pass=2",
       "2 camera pass with shadow test"},
      {"scene=brabec&technique=legacy.pcf&size=96x72&filter=2", "missing@pass=3",
       "3 projective pass: subtract packed map"},
      {"scene=brabec&technique=legacy.fast-pcf&size=96x72&filter=2", "error@pass=3",
       "3 camera pass: light depth in RGBA"},
  };
  for (const Case& c : cases) {
    const std::string path = "/api/render?" + c.query;
    auto before = get(path);
    ASSERT_TRUE(before) << c.query;
    ASSERT_EQ(before->status, 200) << c.query << ": " << before->body;
    const Image clean = decodePng(before->body, dir, "before.png");

    injectGlFault(parseGlFault(c.fault));
    const int fired = glFaultsFired();
    auto failed = get(path);
    ASSERT_TRUE(failed) << c.query;
    EXPECT_EQ(failed->status, 500) << c.query << ": " << failed->body;
    EXPECT_EQ(failed->get_header_value("Content-Type"), "text/plain");
    EXPECT_EQ(failed->body.find('\n'), std::string::npos) << failed->body;
    EXPECT_EQ(failed->body.rfind("GL: ", 0), 0u) << failed->body;
    EXPECT_NE(failed->body.find("(injected GL fault " + c.fault + ", in pass '" + c.pass),
              std::string::npos)
        << failed->body;
    EXPECT_EQ(glFaultsFired(), fired + 1);

    auto after = get(path);
    ASSERT_TRUE(after) << c.query;
    ASSERT_EQ(after->status, 200) << c.query << ": " << after->body;
    const Image again = decodePng(after->body, dir, "after.png");
    // The same technique on a fresh context of the same kind: the same pixels.
    EXPECT_EQ(again.width, clean.width);
    EXPECT_TRUE(again.data == clean.data) << c.query;
  }
}

}  // namespace
}  // namespace sl::test
