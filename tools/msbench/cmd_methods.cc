// msbench methods: the registered exploration methods (core/explorer/method_registry.h), each with
// its summary, the Table I rows it answers to and every key of its `method:` section with its
// default — what a scenario may set.
#include <cstdio>
#include <sstream>

#include "tools/config/key_reference.h"
#include "tools/config/method_table.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"

namespace msb {

namespace {

// The YAML text indented by `pad` spaces.
std::string indented(const std::string& text, const std::string& pad) {
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line)) out += pad + line + "\n";
  return out;
}

void printMethod(const MethodRegistration& reg, bool keys) {
  const MethodInfo& e = reg.info;
  std::printf("%s: %s\n", e.type.c_str(), e.summary.c_str());
  if (!e.paper_rows.empty()) {
    std::string rows;
    for (const PaperRow& r : e.paper_rows)
      rows += std::string(rows.empty() ? "" : ", ") + r.world +
              (*r.switched_off ? std::string(" no ") + r.switched_off : "");
    std::printf("  Table I rows: %s\n", rows.c_str());
  }
  if (takesGoalChooser(registeredMethodChoice(reg, reg.default_config())))
    std::printf("  takes a goal chooser written in Python (a scenario's goals: section)\n");
  if (keys) std::printf("  keys and defaults:\n%s", indented(methodDefaultsYaml(e.type), "    ").c_str());
}

}  // namespace

int runMethodsCommand(int argc, char** argv) {
  ArgParser args("msbench methods",
                 "The registered exploration methods (method.type): summary, the Table I rows each\n"
                 "answers to, and with --type TYPE (or --keys) every key of its method: section with its\n"
                 "default. A method written in Python is method.type: python (docs/python.md).");
  args.option("type", "", "one method's type: it alone, with its keys").flag("keys", "list every method's keys");
  if (!args.parse(argc, argv)) return kExitOk;
  const std::string type = args.get("type");
  if (!type.empty()) {
    const MethodRegistration* e = findRegistration(type);
    if (!e) methodDefaultsYaml(type);  // throws, naming the known types
    if (e) printMethod(*e, true);
    return kExitOk;
  }
  for (const MethodRegistration& reg : methodRegistrations()) printMethod(reg, args.has("keys"));
  return kExitOk;
}

int runKeysCommand(int argc, char** argv) {
  ArgParser args("msbench keys",
                 "Every configuration key a scenario may set (flight, sensors, front end, mission, video,\n"
                 "and each method's method: section), its default and the values it accepts, as the\n"
                 "Markdown of docs/keys.md. Generated from the key tables that validate, read and write them.");
  if (!args.parse(argc, argv)) return kExitOk;
  std::fputs(keyReferenceMarkdown().c_str(), stdout);
  return kExitOk;
}

}  // namespace msb
