// Recursive-descent parser of the scripting language (grammar in
// docs/SCRIPTING.md). Commands are checked here (name, arity, bare words) so
// mistakes are reported before anything runs.
#include "ScriptAst.h"

#include "lvdif/Script.h"
#include "lvdif/QuotedText.h"

#include <map>
#include <set>

namespace lvdif
{
namespace detail::script
{

namespace
{

struct CommandSpec
{
  int minArgs, maxArgs;
  std::set<std::string> words; // non-empty: takes one bare word instead of numbers
};

const std::map<std::string, CommandSpec>& commands()
{
  static const std::map<std::string, CommandSpec> c{
    { "canvas", { 1, 3, {} } }, // canvas n | canvas nx ny nz | canvas fill | canvas clear (words checked below)
    { "color", { 3, 4, {} } },
    { "radius", { 1, 1, {} } },
    { "brush", { 0, 0, { "sphere", "cube" } } },
    { "op", { 0, 0, { "add", "subtract", "paint" } } },
    { "kind", { 0, 0, { "single", "basic", "dynamic", "drill" } } },
    { "blend", { 1, 1, {} } },
    { "round", { 1, 1, {} } },
    { "spacing", { 1, 1, {} } },
    { "dab", { 3, 3, {} } },
    { "line", { 6, 6, {} } },
    { "sphere", { 4, 4, {} } },
    { "cube", { 4, 4, {} } },
    { "begin", { 0, 0, {} } },
    { "point", { 3, 4, {} } },
    { "end", { 0, 0, {} } },
    { "undo", { 0, 0, {} } },
    { "redo", { 0, 0, {} } },
    { "print", { 1, 16, {} } },
  };
  return c;
}

const std::set<std::string>& keywords()
{
  static const std::set<std::string> k{ "for", "in", "while", "if", "else", "let", "and", "or", "not" };
  return k;
}

class Parser
{
public:
  explicit Parser(const std::vector<Token>& t)
    : T(t)
  {
  }

  Program program()
  {
    Program p;
    p.statements = this->block(nullptr);
    return p;
  }

private:
  const std::vector<Token>& T;
  std::size_t I = 0;
  int Depth = 0;  // expression levels (ScriptMaxNesting)
  int Blocks = 0; // nested blocks (ScriptMaxNesting of their own)

  const Token& peek() const { return this->T[this->I]; }
  const Token& next() { return this->T[this->I < this->T.size() - 1 ? this->I++ : this->I]; }
  bool at(Tok k) const { return this->peek().kind == k; }
  bool atWord(const char* w) const { return this->at(Tok::Ident) && this->peek().text == w; }

  [[noreturn]] void fail(const Token& t, const std::string& what) const
  {
    throw ScriptError(ErrorCode::ParseError, t.line, t.column, what);
  }
  static std::string describe(const Token& t)
  {
    if (t.kind == Tok::End)
      return "the end of the script";
    if (t.kind == Tok::Newline)
      return "the end of the line";
    return quotedText(t.text);
  }
  const Token& expect(Tok k, const char* what)
  {
    if (!this->at(k))
      this->fail(this->peek(), std::string("expected ") + what + ", found " + describe(this->peek()));
    return this->next();
  }

  void skipSeparators()
  {
    while (this->at(Tok::Newline) || this->at(Tok::Semicolon))
      this->next();
  }

  // one level of an expression (parentheses, unary operators, calls)
  void enter(const Token& at, const char* what)
  {
    if (++this->Depth > ScriptMaxNesting)
      this->fail(at, std::string(what) + " nested too deeply (more than " + std::to_string(ScriptMaxNesting) +
          " levels of parentheses, unary operators and calls)");
  }

  // statements until '}' (open != nullptr) or the end
  Block block(const Token* open)
  {
    // blocks count on their own: an if's condition is no block level (201
    // nested ifs were "expressions nested too deeply", at 200)
    if (open && ++this->Blocks > ScriptMaxNesting)
      this->fail(*open, "blocks nested too deeply: this '{' opens level " + std::to_string(this->Blocks) +
          ", more than the limit of " + std::to_string(ScriptMaxNesting) + " nested if, else, for and while blocks");
    Block b;
    for (;;)
    {
      this->skipSeparators();
      if (this->at(Tok::RBrace))
      {
        if (!open)
          this->fail(this->peek(), "unexpected '}' without a matching '{'");
        break;
      }
      if (this->at(Tok::End))
      {
        if (open)
          this->fail(*open, "this '{' is never closed");
        break;
      }
      b.push_back(this->statement());
      if (!(this->at(Tok::Newline) || this->at(Tok::Semicolon) || this->at(Tok::RBrace) || this->at(Tok::End)))
        this->fail(this->peek(), "expected the end of the statement, found " + describe(this->peek()));
    }
    if (open)
      --this->Blocks;
    return b;
  }

  Block braced()
  {
    this->skipNewlinesBefore(Tok::LBrace);
    const Token& open = this->expect(Tok::LBrace, "'{'");
    Block b = this->block(&open);
    this->expect(Tok::RBrace, "'}'");
    return b;
  }

  void skipNewlinesBefore(Tok k)
  {
    std::size_t j = this->I;
    while (this->T[j].kind == Tok::Newline)
      ++j;
    if (this->T[j].kind == k)
      this->I = j;
  }

  std::unique_ptr<Stmt> statement()
  {
    const Token& t = this->peek();
    auto s = std::make_unique<Stmt>();
    s->line = t.line;
    s->column = t.column;
    if (t.kind != Tok::Ident)
      this->fail(t, "expected a command, found " + describe(t));
    if (t.text == "for")
    {
      this->next();
      s->kind = Stmt::Kind::For;
      s->name = this->variableName();
      if (!this->atWord("in"))
        this->fail(this->peek(), "expected 'in' after the loop variable, found " + describe(this->peek()));
      this->next();
      s->from = this->expression();
      this->expect(Tok::DotDot, "'..' between the loop bounds");
      s->to = this->expression();
      s->body = this->braced();
      return s;
    }
    if (t.text == "while")
    {
      this->next();
      s->kind = Stmt::Kind::While;
      s->cond = this->expression();
      s->body = this->braced();
      return s;
    }
    if (t.text == "if")
    {
      this->next();
      s->kind = Stmt::Kind::If;
      s->cond = this->expression();
      s->body = this->braced();
      // else-if clauses are collected in a loop, not by recursion
      for (;;)
      {
        this->skipNewlinesBefore(Tok::Ident);
        if (!this->atWord("else"))
        {
          // skipNewlinesBefore may have moved onto the next statement: step back to its newline
          while (this->I > 0 && this->T[this->I - 1].kind == Tok::Newline)
            --this->I;
          break;
        }
        this->next();
        if (!this->atWord("if"))
        {
          s->orelse = this->braced();
          break;
        }
        this->next();
        Stmt::Clause c;
        c.cond = this->expression();
        c.body = this->braced();
        s->elifs.push_back(std::move(c));
      }
      return s;
    }
    if (t.text == "let" || (this->I + 1 < this->T.size() && this->T[this->I + 1].kind == Tok::Assign))
    {
      if (t.text == "let")
        this->next();
      s->kind = Stmt::Kind::Assign;
      s->name = this->variableName();
      this->expect(Tok::Assign, "'='");
      s->cond = this->expression();
      return s;
    }
    if (t.text == "else")
      this->fail(t, "'else' without 'if'");
    auto it = commands().find(t.text);
    if (it == commands().end())
      this->fail(t, "unknown command " + quotedText(t.text));
    this->next();
    s->kind = Stmt::Kind::Command;
    s->name = t.text;
    const CommandSpec& spec = it->second;
    const bool canvasWord = s->name == "canvas" && (this->atWord("fill") || this->atWord("clear"));
    if (!spec.words.empty() || canvasWord)
    {
      const std::set<std::string> words = canvasWord ? std::set<std::string>{ "fill", "clear" } : spec.words;
      std::string list;
      for (const auto& w : words)
        list += (list.empty() ? "" : ", ") + w;
      if (!this->at(Tok::Ident) || !words.count(this->peek().text))
        this->fail(this->peek(), "'" + s->name + "' expects one of: " + list + "; found " + describe(this->peek()));
      s->word = this->next().text;
      return s;
    }
    const std::size_t firstArg = this->I;
    while (!(this->at(Tok::Newline) || this->at(Tok::Semicolon) || this->at(Tok::RBrace) || this->at(Tok::End)))
    {
      s->args.push_back(this->expression());
      if (this->at(Tok::Comma))
        this->next();
    }
    const int n = static_cast<int>(s->args.size());
    if (n < spec.minArgs || n > spec.maxArgs || (s->name == "canvas" && n == 2))
    {
      std::string want = spec.minArgs == spec.maxArgs ? std::to_string(spec.minArgs)
                                                      : std::to_string(spec.minArgs) + (spec.maxArgs == spec.minArgs + 1 ? " or " : " to ") +
          std::to_string(spec.maxArgs); // ("3 to 4 arguments" for color's 3 or 4)
      if (s->name == "canvas")
        want = "1 or 3 (or the word fill or clear)";
      // too few where a '-' with a space before it and none after follows a value ('sphere 1 1 1 -1'
      // said only "takes 4 arguments, got 3"): that minus subtracts
      std::string why;
      for (std::size_t k = firstArg + 1; n < spec.minArgs && why.empty() && k + 1 < this->I; ++k)
      {
        const Token &before = this->T[k - 1], &minus = this->T[k], &after = this->T[k + 1];
        if (minus.kind == Tok::Minus && before.line == minus.line && after.line == minus.line &&
          (before.kind == Tok::Number || before.kind == Tok::Ident || before.kind == Tok::RParen) &&
          before.column + static_cast<int>(before.text.size()) < minus.column && after.column == minus.column + 1)
          why = " (the '-' at column " + std::to_string(minus.column) +
            ", with a space before it and none after, subtracts: separate the arguments with commas when one starts "
            "with a minus, as in 'dab 10, -2, 5')";
      }
      this->fail(t, "'" + s->name + "' takes " + want + " argument" + (want == "1" ? "" : "s") + ", got " +
          std::to_string(n) + why);
    }
    return s;
  }

  std::string variableName()
  {
    const Token& t = this->peek();
    if (t.kind != Tok::Ident)
      this->fail(t, "expected a variable name, found " + describe(t));
    if (keywords().count(t.text) || commands().count(t.text))
      this->fail(t, quotedText(t.text) + " is a reserved word and cannot be a variable");
    return this->next().text;
  }

  // ---- expressions: or > and > comparison > sum > product > unary > primary
  ExprPtr node(Expr::Kind k, const Token& t)
  {
    auto e = std::make_unique<Expr>();
    e->kind = k;
    e->line = t.line;
    e->column = t.column;
    return e;
  }
  ExprPtr expression()
  {
    this->enter(this->peek(), "expressions");
    ExprPtr e = this->orExpr();
    --this->Depth;
    return e;
  }
  // Each level loops over its operators; a parenthesised chain of the same
  // level is its own node (it came back from primary(), not from this loop).
  ExprPtr orExpr()
  {
    ExprPtr a = this->andExpr();
    ExprPtr c;
    while (this->atWord("or"))
    {
      const Token& t = this->next();
      c = this->grow(std::move(c), std::move(a), t, "|", this->andExpr());
    }
    return c ? std::move(c) : std::move(a);
  }
  ExprPtr andExpr()
  {
    ExprPtr a = this->comparison();
    ExprPtr c;
    while (this->atWord("and"))
    {
      const Token& t = this->next();
      c = this->grow(std::move(c), std::move(a), t, "&", this->comparison());
    }
    return c ? std::move(c) : std::move(a);
  }
  /// The first operator makes a new chain node holding `first`; later ones extend it.
  ExprPtr grow(ExprPtr chainNode, ExprPtr first, const Token& t, const std::string& op, ExprPtr b)
  {
    if (!chainNode)
    {
      chainNode = this->node(Expr::Kind::Binary, t);
      chainNode->args.push_back(std::move(first));
    }
    chainNode->ops.push_back(Expr::Op{ op, t.line, t.column });
    chainNode->args.push_back(std::move(b));
    return chainNode;
  }
  ExprPtr comparison()
  {
    ExprPtr a = this->sum();
    const Tok k = this->peek().kind;
    if (k == Tok::Lt || k == Tok::Le || k == Tok::Gt || k == Tok::Ge || k == Tok::Eq || k == Tok::Ne)
    {
      const Token& t = this->next();
      a = this->grow(nullptr, std::move(a), t, t.text, this->sum());
      const Tok k2 = this->peek().kind;
      if (k2 == Tok::Lt || k2 == Tok::Le || k2 == Tok::Gt || k2 == Tok::Ge || k2 == Tok::Eq || k2 == Tok::Ne)
        this->fail(this->peek(), "comparisons cannot be chained; use 'and'");
    }
    return a;
  }
  ExprPtr sum()
  {
    ExprPtr a = this->product();
    ExprPtr c;
    while (this->at(Tok::Plus) || this->at(Tok::Minus))
    {
      const Token& t = this->next();
      c = this->grow(std::move(c), std::move(a), t, t.text, this->product());
    }
    return c ? std::move(c) : std::move(a);
  }
  ExprPtr product()
  {
    ExprPtr a = this->unary();
    ExprPtr c;
    while (this->at(Tok::Star) || this->at(Tok::Slash) || this->at(Tok::Percent))
    {
      const Token& t = this->next();
      c = this->grow(std::move(c), std::move(a), t, t.text, this->unary());
    }
    return c ? std::move(c) : std::move(a);
  }
  ExprPtr unary()
  {
    if (this->at(Tok::Minus) || this->atWord("not"))
    {
      this->enter(this->peek(), "unary operators");
      const Token& t = this->next();
      auto e = this->node(Expr::Kind::Unary, t);
      e->op = t.kind == Tok::Minus ? "-" : "n";
      e->args.push_back(this->unary());
      --this->Depth;
      return e;
    }
    return this->primary();
  }
  ExprPtr primary()
  {
    const Token& t = this->peek();
    if (t.kind == Tok::Number)
    {
      this->next();
      auto e = this->node(Expr::Kind::Number, t);
      e->number = t.number;
      return e;
    }
    if (t.kind == Tok::LParen)
    {
      this->next();
      ExprPtr e = this->expression();
      this->expect(Tok::RParen, "')'");
      return e;
    }
    if (t.kind == Tok::Ident)
    {
      if (keywords().count(t.text))
        this->fail(t, "expected a value, found the keyword " + quotedText(t.text));
      this->next();
      if (this->at(Tok::LParen))
      {
        this->next();
        auto e = this->node(Expr::Kind::Call, t);
        e->name = t.text;
        if (!this->at(Tok::RParen))
        {
          for (;;)
          {
            e->args.push_back(this->expression());
            if (this->at(Tok::Comma))
            {
              this->next();
              continue;
            }
            break;
          }
        }
        this->expect(Tok::RParen, "')' or ',' in the argument list");
        return e;
      }
      auto e = this->node(Expr::Kind::Variable, t);
      e->name = t.text;
      return e;
    }
    this->fail(t, "expected a value, found " + describe(t));
  }
};

} // namespace

Program parse(const std::vector<Token>& tokens)
{
  return Parser(tokens).program();
}

} // namespace detail::script
} // namespace lvdif
