// Tokens and syntax tree of the scripting language (see lvdif/Script.h).
#pragma once

#include "lvdif/Script.h"

#include <memory>
#include <string>
#include <vector>

namespace lvdif
{
namespace detail::script
{

enum class Tok
{
  Number,
  Ident,
  Newline,
  LParen,
  RParen,
  LBrace,
  RBrace,
  Comma,
  Semicolon,
  DotDot,
  Plus,
  Minus,
  Star,
  Slash,
  Percent,
  Assign,
  Eq,
  Ne,
  Lt,
  Le,
  Gt,
  Ge,
  End
};

struct Token
{
  Tok kind = Tok::End;
  std::string text;
  double number = 0;
  int line = 1, column = 1;
};

struct Expr
{
  enum class Kind
  {
    Number,
    Variable,
    Unary,  // op '-' or 'n' (not)
    Binary, // args[0] ops[0] args[1] ops[1] ... left to right, one precedence level
    Call
  };
  /// One operator of a Binary chain: + - * / % < <= > >= == != & (and) | (or).
  struct Op
  {
    std::string op;
    int line = 1, column = 1;
  };
  Kind kind = Kind::Number;
  double number = 0;
  std::string name; // variable or function
  std::string op;   // of a Unary
  std::vector<std::unique_ptr<Expr>> args;
  /// A chain such as 1+1+1+... is one node with n operands and n-1 operators,
  /// so its length never turns into recursion depth (parsing, evaluation or
  /// destruction); only parentheses, unary operators and calls nest.
  std::vector<Op> ops;
  int line = 1, column = 1;
};
using ExprPtr = std::unique_ptr<Expr>;

struct Stmt;
using Block = std::vector<std::unique_ptr<Stmt>>;

struct Stmt
{
  enum class Kind
  {
    Assign, // name = value
    For,    // for name in from..to { body }
    While,  // while cond { body }
    If,     // if cond { body } else if elifs[0].cond { elifs[0].body } ... else { orelse }
    Command // name args...
  };
  Kind kind = Kind::Command;
  std::string name;
  std::string word; // bare-word argument of brush/op/kind/canvas
  std::vector<ExprPtr> args;
  ExprPtr cond, from, to;
  Block body, orelse;
  /// The `else if` clauses of an If, flat (a long chain nests nothing).
  struct Clause
  {
    ExprPtr cond;
    Block body;
  };
  std::vector<Clause> elifs;
  int line = 1, column = 1;
};

struct Program
{
  Block statements;
};

/// Splits source into tokens; throws ScriptError on a bad character or number.
std::vector<Token> lex(const std::string& source);
/// Parses tokens into a program; throws ScriptError.
Program parse(const std::vector<Token>& tokens);

} // namespace detail::script
} // namespace lvdif
