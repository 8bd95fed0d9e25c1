// Tokens and syntax tree of the scripting language (see lvdif/Script.h).
#pragma once

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
    Binary, // op: + - * / % < <= > >= == != & (and) | (or)
    Call
  };
  Kind kind = Kind::Number;
  double number = 0;
  std::string name; // variable or function
  std::string op;
  std::vector<std::unique_ptr<Expr>> args;
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
    If,     // if cond { body } else { orelse }
    Command // name args...
  };
  Kind kind = Kind::Command;
  std::string name;
  std::string word; // bare-word argument of brush/op/kind/canvas
  std::vector<ExprPtr> args;
  ExprPtr cond, from, to;
  Block body, orelse;
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
