// A plugin whose registration returns 42 and leaves its message unterminated: structmd_load_plugin
// returns a status of the header (ARGUMENT, saying which number the plugin returned) and the message
// ends inside the buffer it gave the plugin (issue 37, defect 7).
#include <gtest/gtest.h>

#include <string>

#include "structmd.h"

TEST(MisbehavingPlugin, AStatusOutsideTheHeaderIsAnArgumentError) {
    EXPECT_EQ(structmd_load_plugin(MISBEHAVING_PLUGIN), STRUCTMD_ERR_ARGUMENT);
    const std::string message = structmd_last_error(nullptr);
    EXPECT_NE(message.find("registration failed with status 42, which is not a structmd status"), std::string::npos)
        << message.substr(0, 200);
    const size_t xs = message.size() - message.find_last_not_of('x') - 1;
    EXPECT_EQ(xs, 1023u) << "the plugin's message is the 1,023 bytes before the buffer's last";
}
