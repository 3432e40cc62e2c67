// Name tables: lookup by exact name, and an unknown name refused with its field and the known
// names in table order (what help texts and "known: ..." errors are derived from).
#include <gtest/gtest.h>

#include "virtual_go/common/name_table.h"

namespace vg = virtual_go;

namespace {

struct Fruit {
  std::string name;
  int calories;
};

const vg::NameTable<Fruit> kFruit("fruit", "snack", {{"pear", 57}, {"apple", 52}, {"fig", 74}});

}  // namespace

TEST(NameTable, FindsByExactName) {
  EXPECT_EQ(kFruit.at("apple").calories, 52);
  ASSERT_NE(kFruit.find("fig"), nullptr);
  EXPECT_EQ(kFruit.find("fig")->calories, 74);
  EXPECT_EQ(kFruit.find("Fig"), nullptr);
  EXPECT_EQ(kFruit.find("fig "), nullptr);
  EXPECT_EQ(kFruit.names(), (std::vector<std::string>{"pear", "apple", "fig"}));
}

TEST(NameTable, UnknownNameNamesTheFieldAndTheKnownNamesInOrder) {
  try {
    kFruit.at("plum");
    ADD_FAILURE() << "plum accepted";
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "snack");
    EXPECT_EQ(std::string(e.what()), "unknown fruit 'plum' (known: pear apple fig)");
  }
}
