// The second registration of `twice` (see method_registry_clash_test.cc).
#include "tests/core/explorer/method_registry_clash.h"

namespace msb {

const MethodRegistrar kSecond = registerMethod<ClashExplorer, ClashConfig>({"twice", "the second", {}});

}  // namespace msb
