// The strict OBJ pass (core/obj_validation.h): every number parsed to its end and finite, every
// index an in-range integer, or an InputError "file:line: reason"; valid files pass untouched.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/obj_validation.h"

namespace kasha {
namespace {

// The message validateObjText throws for `text`, or "" if it accepts it.
std::string problem(const std::string& text) {
  try {
    validateObjText(text, "m.obj");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(ObjValidation, AcceptsWhatTinyobjloaderReadsExactly) {
  EXPECT_EQ(problem(""), "");
  EXPECT_EQ(problem("# comment only\n\n"), "");
  EXPECT_EQ(problem(kTriangle + "f 1 2 3\n"), "");
  EXPECT_EQ(problem("o quad\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nf 1 2 3 4\r\n"), "");  // CRLF, a polygon
  EXPECT_EQ(problem("v +1.5e-3 -2 .5 1\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0  # a comment\nf -3 -2 -1\n"), "");
  EXPECT_EQ(problem(kTriangle + "vt 0 0\nvt 1\nvt 0 1 0\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1//1 2//1 3//1\nf 1/1 2/2 3/3\n"),
            "");
  EXPECT_EQ(problem(kTriangle + "l 1 2\np 3\ng group\ns off\nusemtl x\nmtllib x.mtl\n"), "");
}

TEST(ObjValidation, NumbersMustBeParsedFullyAndFinite) {
  // tinyobjloader alone turns the first two into (0, 1, 0) and the origin.
  EXPECT_EQ(problem("v nan 1 0\n"), "m.obj:1: 'nan' is not a finite number (v component 1)");
  EXPECT_EQ(problem("v a b c\n"), "m.obj:1: 'a' is not a finite number (v component 1)");
  EXPECT_EQ(problem("v 0 0 0\nv 1 inf 0\n"), "m.obj:2: 'inf' is not a finite number (v component 2)");
  EXPECT_EQ(problem("v 1 2 3x\n"), "m.obj:1: '3x' is not a finite number (v component 3)");
  EXPECT_EQ(problem("v 1e39 0 0\n"), "m.obj:1: '1e39' is not a finite number (v component 1)");  // beyond a float
  EXPECT_EQ(problem("vt 0.5 0,5\n"), "m.obj:1: '0,5' is not a finite number (vt component 2)");
  // A lone carriage return ends a line for tinyobjloader (a fuzzing finding): so it does here.
  EXPECT_EQ(problem("u\rvn inf 1 0\n"), "m.obj:2: 'inf' is not a finite number (vn component 1)");
  EXPECT_EQ(problem("v 1\v2 3\n"), "m.obj:1: 'v' takes 3 or 4 or 6 or 7 numbers, found 2");
  EXPECT_EQ(problem("vn 0 0\n"), "m.obj:1: 'vn' takes 3 numbers, found 2");
  EXPECT_EQ(problem("v 0 0\n"), "m.obj:1: 'v' takes 3 or 4 or 6 or 7 numbers, found 2");
}

TEST(ObjValidation, IndicesMustBeIntegersInRange) {
  // Past 2^63: tinyobjloader wraps it to -1 (the last vertex).
  EXPECT_EQ(problem(kTriangle + "f 1 2 9223372036854775809\n"),
            "m.obj:4: corner '9223372036854775809': '9223372036854775809' is not an integer index");
  EXPECT_EQ(problem(kTriangle + "f 1 2 4\n"),
            "m.obj:4: corner '4' refers to vertex 4, but 3 vertices are defined before this line");
  EXPECT_EQ(problem(kTriangle + "f 0 1 2\n"), "m.obj:4: corner '0' refers to vertex 0, but 3 vertices are defined before this line");
  EXPECT_EQ(problem(kTriangle + "f -4 1 2\n"),
            "m.obj:4: corner '-4' refers to vertex -4, but 3 vertices are defined before this line");
  EXPECT_EQ(problem("f 1 2 3\n" + kTriangle), "m.obj:1: corner '1' refers to vertex 1, but 0 vertices are defined before this line");
  EXPECT_EQ(problem(kTriangle + "f 1.5 2 3\n"), "m.obj:4: corner '1.5': '1.5' is not an integer index");
  EXPECT_EQ(problem(kTriangle + "vt 0 0\nf 1/2 2/1 3/1\n"),
            "m.obj:5: corner '1/2' refers to texture coordinate 2, but 1 texture coordinate is defined before this line");
  EXPECT_EQ(problem(kTriangle + "f 1//1 2//1 3//1\n"),
            "m.obj:4: corner '1//1' refers to normal 1, but 0 normals are defined before this line");
  EXPECT_EQ(problem(kTriangle + "f 1/ 2 3\n"), "m.obj:4: corner '1/': '' is not an integer index");
  EXPECT_EQ(problem(kTriangle + "f 1/1/1/1 2 3\n"), "m.obj:4: corner '1/1/1/1' has more than three indices");
  EXPECT_EQ(problem(kTriangle + "f 1 2\n"), "m.obj:4: a face needs at least 3 corners, found 2");
}

TEST(ObjValidation, ReturnsTheTextWithoutCommentsAndKeepsLineEnds) {
  EXPECT_EQ(validateObjText("v 0 0 0  # origin\r\n#x\rf 1 1 1\n", "m.obj"), "v 0 0 0  \r\n\rf 1 1 1\n");
  // A fuzzing finding: tinyobjloader reads "3# 21" as corners 3 and 21; the comment is checked and
  // handed on as nothing, so the face has the three corners that were checked.
  EXPECT_EQ(validateObjText(kTriangle + "f 1 2 3# 21\n", "m.obj"), kTriangle + "f 1 2 3\n");
  EXPECT_EQ(problem(kTriangle + "f 1 2 3 # 21\n2 4\n"), "");
}

}  // namespace
}  // namespace kasha
