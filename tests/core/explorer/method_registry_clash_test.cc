// Two method folders registering one type name (the second is method_registry_clash_other.cc):
// the program starts (no abort before main()), and asking for the methods is an error naming
// both source files; a malformed name and a key clashing with `method.type` are named with
// their file too, and so are hooks offered twice or under a malformed name.
#include <gtest/gtest.h>

#include "core/explorer/method_registry.h"
#include "tests/core/explorer/method_registry_clash.h"

namespace msb {
namespace {

const MethodRegistrar kFirst = registerMethod<ClashExplorer, ClashConfig>({"twice", "the first", {}});
const MethodRegistrar kEmpty = registerMethod<ClashExplorer, ClashConfig>({"", "no name", {}});
const MethodRegistrar kTyped = registerMethod<ClashExplorer, TypedConfig>({"typed", "a key named type", {}});
// Hooks (MethodInfo::hooks): one name offered twice, a name that is not one.
void noop(Explorer&, const std::any&) {}
const MethodRegistrar kHookTwice = registerMethod<ClashExplorer, ClashConfig>(
    {"hook_twice", "one hook name twice", {}, {}, kListedAfterThePaper, {{"chooser", noop}, {"chooser", noop}}});
const MethodRegistrar kHookName = registerMethod<ClashExplorer, ClashConfig>(
    {"hook_name", "a hook named badly", {}, {}, kListedAfterThePaper, {{"a chooser", noop}}});

TEST(MethodRegistry, ADuplicateOrEmptyTypeIsAnErrorNamingTheFilesNotAnAbort) {
  try {
    registeredMethods();
    FAIL() << "no error";
  } catch (const MethodRegistryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'twice' is registered twice"), std::string::npos) << what;
    EXPECT_NE(what.find("method_registry_clash_test.cc"), std::string::npos) << what;
    EXPECT_NE(what.find("method_registry_clash_other.cc"), std::string::npos) << what;
    EXPECT_NE(what.find("method type ''"), std::string::npos) << what;
    // A key of the method's that clashes with the section's own (before: accepted, and the
    // method's `type` key could never be set).
    EXPECT_NE(what.find("method_registry_clash_test.cc: method 'typed' has a key named 'type'"), std::string::npos)
        << what;
    EXPECT_NE(what.find("method_registry_clash_test.cc: method 'hook_twice' offers the hook 'chooser' twice"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("method_registry_clash_test.cc: method 'hook_name' offers a hook named 'a chooser'"),
              std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace msb
