// gl::ProgramCache (one program per shader files + defines) and the shader loader's #line
// directives: a compile error in an included file names that file and its line.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "gl/objects.h"
#include "gl/program_cache.h"
#include "gl/shader_source.h"
#include "render_test_util.h"

namespace penumbra::test {
namespace {

// A folder for $PENUMBRA_SHADER_DIR holding shared.h (the ground floor) and the given files; removed at the end.
struct ShaderDir {
  char path[32] = "/tmp/penumbra-shaders-XXXXXX";
  ShaderDir() {
    EXPECT_NE(mkdtemp(path), nullptr);
    write("shared.h", gl::shaderSource("shared.h"));
  }
  ~ShaderDir() {
    unsetenv("PENUMBRA_SHADER_DIR");
    std::filesystem::remove_all(path);
  }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(std::string(path) + "/" + name) << text;
  }
  void use() { setenv("PENUMBRA_SHADER_DIR", path, 1); }
};

std::string compileError(const std::vector<std::string>& files) {
  try {
    gl::Program p(files);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// $PENUMBRA_SHADER_DIR lists folders (':'-separated, as shaders live beside the code that runs
// them): a file is read from the first that holds it, empty entries are skipped, and a file none
// holds is an error naming the list.
TEST(ShaderLoader, SearchPathReadsTheFirstFolderHoldingTheFile) {
  ShaderDir first, second;
  first.write("a.glsl", "// a from the first\n");
  second.write("a.glsl", "// a from the second\n");
  second.write("b.glsl", "// b from the second\n");
  const std::string path = std::string(first.path) + "::" + second.path;
  setenv("PENUMBRA_SHADER_DIR", path.c_str(), 1);
  EXPECT_EQ(gl::shaderSource("a.glsl"), "// a from the first\n");
  EXPECT_EQ(gl::shaderSource("b.glsl"), "// b from the second\n");
  try {
    gl::shaderSource("c.glsl");
    ADD_FAILURE() << "no error for a shader no folder holds";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "c.glsl: no such shader in PENUMBRA_SHADER_DIR (" + path + ")");
  }
}

TEST(ShaderLoader, ErrorInAnIncludedFileNamesThatFileAndLine) {
  context();
  ShaderDir dir;
  // The error is on line 3 of inner.glsl, included from line 2 of outer.glsl, itself included
  // from line 2 of the stage; probe2's own error after the includes is on its line 4.
  dir.write("inner.glsl", "// inner\nfloat ok() { return 1.0; }\nfloat bad() { return undefinedInInner; }\n");
  dir.write("outer.glsl", "// outer\n#include \"inner.glsl\"\nfloat two() { return 2.0; }\n");
  dir.write("probe.frag",
            "// probe\n#include \"outer.glsl\"\nout vec4 colour;\nvoid main() { colour = vec4(ok() + two()); }\n");
  dir.write(
      "probe2.frag",
      "// probe 2\n#include \"outer.glsl\"\nout vec4 colour;\nvoid main() { colour = vec4(undefinedInStage); }\n");
  dir.write("fullscreen.vert", gl::shaderSource("fullscreen.vert"));
  dir.use();
  const std::string e1 = compileError({"fullscreen.vert", "probe.frag"});
  EXPECT_NE(e1.find("probe.frag: compile error: inner.glsl:3"), std::string::npos) << e1;
  const std::string e2 = compileError({"fullscreen.vert", "probe2.frag"});
  EXPECT_NE(e2.find("probe2.frag: compile error: inner.glsl:3"), std::string::npos) << e2;
  EXPECT_NE(e2.find("probe2.frag:4("), std::string::npos) << e2;
  gl::Context::takeErrorCount();
}

// A stage gets only the defines its text (with its includes) names, so that a stage that does
// not depend on a define compiles to the same text in every variant of a program and the
// driver's shader cache compiles it once (dcs's geometry shader across counter layouts).
TEST(ShaderLoader, AStageGetsOnlyTheDefinesItNames) {
  ShaderDir dir;
  dir.write("inc.glsl", "#ifdef FROM_INCLUDE\n#endif\n");
  dir.write("probe.frag", "#include \"inc.glsl\"\nfloat f() { return float(USED) + VALUE_X; }\n");
  dir.use();
  const std::string text =
      gl::assembleShader("probe.frag", {"USED 2", "UNUSED 3", "VALUE 4", "FROM_INCLUDE", "VALUE_X(a) a"}).text;
  EXPECT_NE(text.find("#define USED 2\n"), std::string::npos) << text;
  EXPECT_NE(text.find("#define FROM_INCLUDE\n"), std::string::npos) << text;
  EXPECT_NE(text.find("#define VALUE_X(a) a\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("UNUSED"), std::string::npos) << text;
  EXPECT_EQ(text.find("VALUE 4"), std::string::npos) << text;  // VALUE_X is another name
  EXPECT_EQ(gl::assembleShader("probe.frag", {"USED 2", "UNUSED 3"}).text,
            gl::assembleShader("probe.frag", {"USED 2", "UNUSED 5"}).text);
}

TEST(ShaderLoader, LogLocationsNameTheirFiles) {
  const std::vector<std::string> files = {"a.frag", "shared.h", "b.glsl"};
  EXPECT_EQ(gl::nameLogLocations("0:4(12): error: x\n0:200007(1): error: y\n", files),
            "a.frag:4(12): error: x b.glsl:7(1): error: y");
  EXPECT_EQ(gl::nameLogLocations("0(200007) : error C1008: z\n", files), "b.glsl:7 : error C1008: z");
  // A line that encodes no file it knows stays as the driver wrote it.
  EXPECT_EQ(gl::nameLogLocations("0:900001(1): error\n", files), "0:900001(1): error");
}

TEST(ProgramCache, OneProgramPerFilesAndDefines) {
  context();
  gl::ProgramCache cache;
  const gl::Program& a = cache.get({"fullscreen.vert", "pipeline_resolve.frag"}, {"UNSHADOWED"});
  const gl::Program& b = cache.get({"fullscreen.vert", "pipeline_resolve.frag"}, {"UNSHADOWED"});
  const gl::Program& c = cache.get({"fullscreen.vert", "pipeline_resolve.frag"}, {"COUNTER"});
  EXPECT_EQ(&a, &b);
  EXPECT_EQ(a.id(), b.id());
  EXPECT_NE(a.id(), c.id());
  EXPECT_EQ(cache.size(), 2u);
  cache.clear();
  EXPECT_EQ(cache.size(), 0u);
}

}  // namespace
}  // namespace penumbra::test
