#include "util/csv_table.h"

#include <gtest/gtest.h>

#include "util/test_error.h"

namespace vaegail {
namespace {

TEST(CsvTable, ReadsNumbersAndStringsByColumnName) {
  const auto t = CsvTable::parse("episode,expert_id,speed\r\n0,walker-a,1.5\n\n1,walker-b,-2e-1\n", "e.csv");
  EXPECT_EQ(t.rows(), 2);
  EXPECT_EQ(t.columns(), (std::vector<std::string>{"episode", "expert_id", "speed"}));
  EXPECT_EQ(t.numbers("speed"), (std::vector<double>{1.5, -0.2}));
  EXPECT_EQ(t.strings("expert_id"), (std::vector<std::string>{"walker-a", "walker-b"}));
  EXPECT_TRUE(t.has_column("episode"));
  EXPECT_FALSE(t.has_column("missing"));
}

TEST(CsvTable, ErrorsNameFileLineAndColumn) {
  const auto t = CsvTable::parse("a,b\n1,2\n3,nan\n4,x\n", "m.csv");
  EXPECT_EQ(error_of([&] { t.numbers("c"); }), "m.csv: no column 'c' (columns: a, b)");
  EXPECT_EQ(error_of([&] { t.numbers("b"); }), "m.csv: line 3: column 'b': 'nan' is not a finite number");
  EXPECT_EQ(error_of([] { CsvTable::parse("a,b\n1\n", "r.csv"); }), "r.csv: line 2: 1 cells, header has 2");
  EXPECT_EQ(error_of([] { CsvTable::parse("a,b\n1,\n", "r.csv").numbers("b"); }),
            "r.csv: line 2: column 'b': '' is not a finite number");
  EXPECT_EQ(error_of([] { CsvTable::parse("\n", "e.csv"); }), "e.csv: no header row (empty file)");
  std::string wide = "c0";
  for (int i = 1; i < 20; ++i) wide += ",c" + std::to_string(i);
  EXPECT_EQ(error_of([&] { CsvTable::parse(wide + "\n", "w.csv").numbers("x"); }),
            "w.csv: no column 'x' (columns: c0, c1, c2, c3, c4, c5, c6, c7, c8, c9, c10, c11, ... 20 in all)");
  EXPECT_NE(error_of([] { CsvTable::read("/nonexistent/m.csv"); }).find("/nonexistent/m.csv"), std::string::npos);
}

}  // namespace
}  // namespace vaegail
