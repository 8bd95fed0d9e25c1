// A main() for compilers without libFuzzer: runs the fuzz target once per file
// named on the command line (a corpus replay, used as a regression test).
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv)
{
  int n = 0;
  for (int i = 1; i < argc; ++i)
  {
    std::ifstream in(argv[i], std::ios::binary);
    if (!in)
    {
      std::fprintf(stderr, "cannot read %s\n", argv[i]);
      return 1;
    }
    const std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
    ++n;
  }
  std::printf("replayed %d inputs\n", n);
  return 0;
}
